// Integrator settings: string key/values from the scene's `integrator:` block and the
// CLI's `--set key=value`, read through typed getters that record the default and a
// one-line documentation string. After an integrator has read its settings,
// `check_all_used()` turns any key nobody asked for into an error (no silent typos).
// `to_json()` writes back every resolved value for the JSON sidecar.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/json.h"

namespace dp::integrators {

class Settings {
 public:
  // Later sets override earlier ones; `origin` names where a value came from
  // ("scene.yaml", "--set") for error messages.
  void set(const std::string& key, const std::string& value, const std::string& origin = "--set");
  bool has(const std::string& key) const { return m_values.count(key) != 0; }

  int get_int(const std::string& key, int def, const std::string& doc);
  double get_double(const std::string& key, double def, const std::string& doc);
  bool get_bool(const std::string& key, bool def, const std::string& doc);
  std::string get_string(const std::string& key, const std::string& def, const std::string& doc,
                         const std::vector<std::string>& allowed = {});

  // Throws dp::ValueError naming the first key that no getter read.
  void check_all_used(const std::string& integrator) const;
  core::Json to_json() const;
  // Every resolved (key, value), in the order the integrator read them.
  std::vector<std::pair<std::string, std::string>> values() const;
  // "key = default: doc" lines for --help style listings.
  std::string describe() const;

 private:
  struct Entry {
    std::string value, origin;
  };
  struct Resolved {
    std::string value, doc;
  };
  const Entry* find(const std::string& key, const std::string& doc, const std::string& def);
  std::map<std::string, Entry> m_values;
  std::map<std::string, bool> m_used;
  std::vector<std::pair<std::string, Resolved>> m_resolved;
};

}  // namespace dp::integrators
