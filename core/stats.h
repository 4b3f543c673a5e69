// Statistics counters (shift failures by cause, NaN drops, manifold iterations, ...).
// Each thread owns a `Stats`; they are merged at the end of a render and written to
// the JSON sidecar. Counter names are dotted ("pt.nan_dropped").
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace dp::core {

class Stats {
 public:
  void add(const std::string& name, int64_t value = 1) { m_counters[name] += value; }
  int64_t get(const std::string& name) const {
    auto it = m_counters.find(name);
    return it == m_counters.end() ? 0 : it->second;
  }
  void merge(const Stats& other) {
    for (const auto& [k, v] : other.m_counters) m_counters[k] += v;
  }
  const std::map<std::string, int64_t>& counters() const { return m_counters; }

 private:
  std::map<std::string, int64_t> m_counters;
};

}  // namespace dp::core
