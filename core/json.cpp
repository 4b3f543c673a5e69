#include "core/json.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace dp::core {

std::string json_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size() + 2);
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

Json& Json::operator[](const std::string& key) {
  if (std::holds_alternative<std::nullptr_t>(m_value)) m_value = Object{};
  DP_CHECK(std::holds_alternative<Object>(m_value), "Json: not an object");
  auto& obj = std::get<Object>(m_value);
  for (auto& [k, v] : obj)
    if (k == key) return v;
  obj.emplace_back(key, Json());
  return obj.back().second;
}

void Json::push_back(Json v) {
  if (std::holds_alternative<std::nullptr_t>(m_value)) m_value = Array{};
  DP_CHECK(std::holds_alternative<Array>(m_value), "Json: not an array");
  std::get<Array>(m_value).push_back(std::move(v));
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  out += '\n';
  return out;
}

void Json::dump_to(std::string& out, int indent, int depth) const {
  const std::string pad = indent > 0 ? "\n" + std::string(size_t(indent * (depth + 1)), ' ') : "";
  const std::string pad_end = indent > 0 ? "\n" + std::string(size_t(indent * depth), ' ') : "";
  if (std::holds_alternative<std::nullptr_t>(m_value)) {
    out += "null";
  } else if (auto b = std::get_if<bool>(&m_value)) {
    out += *b ? "true" : "false";
  } else if (auto d = std::get_if<double>(&m_value)) {
    if (!std::isfinite(*d)) {
      out += "null";
    } else if (*d == std::floor(*d) && std::abs(*d) < 1e15) {
      out += std::to_string(int64_t(*d));
    } else {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9g", *d);
      out += buf;
    }
  } else if (auto s = std::get_if<std::string>(&m_value)) {
    out += '"' + json_escape(*s) + '"';
  } else if (auto a = std::get_if<Array>(&m_value)) {
    out += '[';
    for (size_t i = 0; i < a->size(); ++i) {
      if (i) out += ',';
      out += pad;
      (*a)[i].dump_to(out, indent, depth + 1);
    }
    if (!a->empty()) out += pad_end;
    out += ']';
  } else if (auto o = std::get_if<Object>(&m_value)) {
    out += '{';
    for (size_t i = 0; i < o->size(); ++i) {
      if (i) out += ',';
      out += pad + '"' + json_escape((*o)[i].first) + "\":" + (indent > 0 ? " " : "");
      (*o)[i].second.dump_to(out, indent, depth + 1);
    }
    if (!o->empty()) out += pad_end;
    out += '}';
  }
}

}  // namespace dp::core
