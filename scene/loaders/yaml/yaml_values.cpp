#include "scene/loaders/yaml/yaml_values.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/number_syntax.h"
#include "scene/limits.h"

namespace dp::scene::yaml {

namespace {

std::string quoted(const std::string& s) { return "'" + quote_input(s) + "'"; }

const char* type_name(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "a scalar";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "an undefined value";
  }
}

// A plain (unquoted) scalar: quoted scalars are strings, never numbers or booleans.
bool is_plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

bool is_nonfinite_spelling(std::string s) {
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s == ".inf" || s == "inf" || s == "infinity" || s == ".nan" || s == "nan";
}

void expect_list_of(const Context& ctx, const YAML::Node& node, const std::string& name, size_t n) {
  if (!node.IsSequence() || node.size() != n)
    parse_error(ctx, node,
                quoted(name) + ": expected a list of " + std::to_string(n) + " numbers, got " +
                    (node.IsSequence() ? "a list of " + std::to_string(node.size()) : std::string(type_name(node))));
}

}  // namespace

int line_of(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;
  const YAML::Mark m = node.Mark();
  return m.line >= 0 ? m.line + 1 : 0;
}

void parse_error(const Context& ctx, const YAML::Node& at, const std::string& message) {
  throw ParseError(message, ctx.file, line_of(at));
}

void value_error(const Context& ctx, const YAML::Node& at, const std::string& message) {
  throw ValueError(message, ctx.file, line_of(at));
}

void expect_map(const Context& ctx, const YAML::Node& node, const std::string& what) {
  if (!node.IsMap()) parse_error(ctx, node, what + ": expected a map, got " + type_name(node));
}

void expect_sequence(const Context& ctx, const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence()) parse_error(ctx, node, what + ": expected a list, got " + type_name(node));
}

void check_keys(const Context& ctx, const YAML::Node& map, const std::vector<std::string_view>& allowed,
                const std::string& what) {
  expect_map(ctx, map, what);
  std::set<std::string> seen;
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (!it->first.IsScalar()) parse_error(ctx, it->first, what + ": keys must be plain names");
    const std::string key = it->first.Scalar();
    bool ok = false;
    for (std::string_view a : allowed) ok |= (a == key);
    if (!ok) {
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      parse_error(ctx, it->first, "unknown key " + quoted(quote_input(key)) + " in " + what + " (allowed: " + list + ")");
    }
    if (!seen.insert(key).second) parse_error(ctx, it->first, "duplicate key " + quoted(quote_input(key)) + " in " + what);
  }
}

YAML::Node require(const Context& ctx, const YAML::Node& map, const std::string& key, const std::string& what) {
  expect_map(ctx, map, what);
  const YAML::Node v = map[key];
  if (!v.IsDefined() || v.IsNull()) parse_error(ctx, map, "missing required key " + quoted(key) + " in " + what);
  return v;
}

double get_number(const Context& ctx, const YAML::Node& node, const std::string& name) {
  if (!is_plain_scalar(node)) parse_error(ctx, node, quoted(name) + ": expected a number, got " + type_name(node));
  const std::string& s = node.Scalar();
  if (is_nonfinite_spelling(s)) value_error(ctx, node, quoted(name) + ": not a finite number (" + quote_input(s) + ")");
  if (!core::is_decimal_number(s))  // std::strtod alone would also read hex ("0x10")
    parse_error(ctx, node, quoted(name) + ": expected a number, got '" + quote_input(s) + "'");
  errno = 0;
  const double v = std::strtod(s.c_str(), nullptr);
  if (errno == ERANGE || !std::isfinite(v))
    value_error(ctx, node, quoted(name) + ": not a finite number (" + quote_input(s) + ")");
  return v;
}

float get_float(const Context& ctx, const YAML::Node& node, const std::string& name) {
  const double v = get_number(ctx, node, name);
  const std::string& s = node.Scalar();
  if (!within_scene_limit(v))
    value_error(ctx, node, quoted(name) + ": " + quote_input(s) + " is beyond the scene limit (magnitude at most " +
                               kMaxSceneMagnitudeText + ")");
  return static_cast<float>(v);
}

long long get_integer(const Context& ctx, const YAML::Node& node, const std::string& name) {
  if (!is_plain_scalar(node)) parse_error(ctx, node, quoted(name) + ": expected an integer, got " + type_name(node));
  const std::string& s = node.Scalar();
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size())
    parse_error(ctx, node, quoted(name) + ": expected an integer, got '" + quote_input(s) + "'");
  if (errno == ERANGE) value_error(ctx, node, quoted(name) + ": integer out of range (" + quote_input(s) + ")");
  return v;
}

int get_int(const Context& ctx, const YAML::Node& node, const std::string& name) {
  const long long v = get_integer(ctx, node, name);
  if (v > 1'000'000'000LL || v < -1'000'000'000LL)
    value_error(ctx, node, quoted(name) + ": integer out of range (" + quote_input(node.Scalar()) + ")");
  return int(v);
}

std::vector<YAML::Node> get_list(const Context& ctx, const YAML::Node& node, const std::string& name, bool allow_scalar) {
  std::vector<YAML::Node> out;
  if (allow_scalar && node.IsScalar()) {
    out.push_back(node);
    return out;
  }
  if (!node.IsSequence()) parse_error(ctx, node, quoted(name) + ": expected a list, got " + type_name(node));
  for (const auto& n : node) out.push_back(n);
  return out;
}

bool get_bool(const Context& ctx, const YAML::Node& node, const std::string& name) {
  if (is_plain_scalar(node)) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  parse_error(ctx, node, quoted(name) + ": expected true or false, got " +
                             (node.IsScalar() ? "'" + quote_input(node.Scalar()) + "'" : std::string(type_name(node))));
}

std::string get_string(const Context& ctx, const YAML::Node& node, const std::string& name) {
  if (!node.IsScalar() || node.Scalar().empty())
    parse_error(ctx, node, quoted(name) + ": expected a name or text, got " + type_name(node));
  return node.Scalar();
}

Vec2 get_vec2(const Context& ctx, const YAML::Node& node, const std::string& name) {
  expect_list_of(ctx, node, name, 2);
  return Vec2(get_float(ctx, node[0], name), get_float(ctx, node[1], name));
}

Vec3 get_vec3(const Context& ctx, const YAML::Node& node, const std::string& name) {
  expect_list_of(ctx, node, name, 3);
  return Vec3(get_float(ctx, node[0], name), get_float(ctx, node[1], name), get_float(ctx, node[2], name));
}

Rgb get_rgb(const Context& ctx, const YAML::Node& node, const std::string& name) {
  Rgb c;
  if (node.IsScalar()) {
    c = Rgb::Constant(get_float(ctx, node, name));
  } else if (node.IsSequence() && node.size() == 3) {
    c = Rgb(get_float(ctx, node[0], name), get_float(ctx, node[1], name), get_float(ctx, node[2], name));
  } else {
    parse_error(ctx, node, quoted(name) + ": expected an RGB list [r, g, b] or a number, got " +
                               (node.IsSequence() ? "a list of " + std::to_string(node.size())
                                                  : std::string(type_name(node))));
  }
  if ((c < 0.0f).any()) value_error(ctx, node, quoted(name) + ": colour components must be >= 0");
  return c;
}

Vec3 get_direction(const Context& ctx, const YAML::Node& node, const std::string& name) {
  const Vec3 d = get_vec3(ctx, node, name);
  const float len = d.norm();
  if (!(len > 0.0f) || !std::isfinite(len)) value_error(ctx, node, quoted(name) + ": direction must be non-zero");
  return d / len;
}

float get_float_or(const Context& ctx, const YAML::Node& map, const std::string& key, float fallback) {
  const YAML::Node v = map[key];
  return v.IsDefined() ? get_float(ctx, v, key) : fallback;
}

std::string get_string_or(const Context& ctx, const YAML::Node& map, const std::string& key,
                          const std::string& fallback) {
  const YAML::Node v = map[key];
  return v.IsDefined() ? get_string(ctx, v, key) : fallback;
}

void check_positive(const Context& ctx, const YAML::Node& node, const std::string& name, float v) {
  if (!(v > 0.0f)) {
    std::ostringstream os;
    os << quoted(name) << " must be > 0 (got " << v << ")";
    value_error(ctx, node, os.str());
  }
}

void check_nonnegative(const Context& ctx, const YAML::Node& node, const std::string& name, float v) {
  if (!(v >= 0.0f)) {
    std::ostringstream os;
    os << quoted(name) << " must be >= 0 (got " << v << ")";
    value_error(ctx, node, os.str());
  }
}

std::string resolve_path(const Context& ctx, const std::string& relative) {
  const std::filesystem::path p(relative);
  if (p.is_absolute() || ctx.base_dir.empty()) return p.lexically_normal().string();
  return (ctx.base_dir / p).lexically_normal().string();
}

std::string to_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

}  // namespace dp::scene::yaml
