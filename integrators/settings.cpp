#include "integrators/settings.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace dp::integrators {

void Settings::set(const std::string& key, const std::string& value, const std::string& origin) {
  m_values[key] = Entry{value, origin};
  m_used[key] = false;
}

const Settings::Entry* Settings::find(const std::string& key, const std::string& doc, const std::string& def) {
  auto it = m_values.find(key);
  const std::string resolved = it == m_values.end() ? def : it->second.value;
  auto r = std::find_if(m_resolved.begin(), m_resolved.end(), [&](const auto& p) { return p.first == key; });
  if (r == m_resolved.end()) m_resolved.push_back({key, Resolved{resolved, doc}});
  else r->second = Resolved{resolved, doc};
  if (it == m_values.end()) return nullptr;
  m_used[key] = true;
  return &it->second;
}

namespace {
[[noreturn]] void bad_value(const std::string& key, const std::string& value, const std::string& origin,
                            const std::string& expected) {
  throw ValueError("setting '" + key + "' = '" + value + "': expected " + expected, origin);
}
}  // namespace

int Settings::get_int(const std::string& key, int def, const std::string& doc) {
  const Entry* e = find(key, doc, std::to_string(def));
  if (!e) return def;
  try {
    size_t pos = 0;
    const long v = std::stol(e->value, &pos);
    if (pos != e->value.size()) bad_value(key, e->value, e->origin, "an integer");
    return int(v);
  } catch (const std::logic_error&) {
    bad_value(key, e->value, e->origin, "an integer");
  }
}

double Settings::get_double(const std::string& key, double def, const std::string& doc) {
  std::ostringstream d;
  d << def;
  const Entry* e = find(key, doc, d.str());
  if (!e) return def;
  try {
    size_t pos = 0;
    const double v = std::stod(e->value, &pos);
    if (pos != e->value.size() || !std::isfinite(v)) bad_value(key, e->value, e->origin, "a finite number");
    return v;
  } catch (const std::logic_error&) {
    bad_value(key, e->value, e->origin, "a number");
  }
}

bool Settings::get_bool(const std::string& key, bool def, const std::string& doc) {
  const Entry* e = find(key, doc, def ? "true" : "false");
  if (!e) return def;
  if (e->value == "true" || e->value == "1" || e->value == "yes") return true;
  if (e->value == "false" || e->value == "0" || e->value == "no") return false;
  bad_value(key, e->value, e->origin, "true or false");
}

std::string Settings::get_string(const std::string& key, const std::string& def, const std::string& doc,
                                 const std::vector<std::string>& allowed) {
  const Entry* e = find(key, doc, def);
  if (!e) return def;
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), e->value) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : " | ") + a;
    bad_value(key, e->value, e->origin, list);
  }
  return e->value;
}

void Settings::check_all_used(const std::string& integrator) const {
  for (const auto& [key, used] : m_used) {
    if (used) continue;
    std::string known;
    for (const auto& [k, r] : m_resolved) known += (known.empty() ? "" : ", ") + k;
    throw ValueError("unknown setting '" + key + "' for integrator '" + integrator + "' (known: " + known + ")",
                     m_values.at(key).origin);
  }
}

core::Json Settings::to_json() const {
  core::Json j = core::Json::object();
  for (const auto& [k, r] : m_resolved) j[k] = r.value;
  return j;
}

std::vector<std::pair<std::string, std::string>> Settings::values() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [k, r] : m_resolved) out.emplace_back(k, r.value);
  return out;
}

std::string Settings::describe() const {
  std::string out;
  for (const auto& [k, r] : m_resolved) out += "  " + k + " = " + r.value + "  : " + r.doc + "\n";
  return out;
}

}  // namespace dp::integrators
