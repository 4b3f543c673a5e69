// Range checks of the CLI's numeric options (issue 18: extreme values are usage errors,
// never aborts or silently ignored values). CLI11 reports a failed check as one usage
// line naming the option.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>

#include "core/number_syntax.h"

namespace dp::apps {

constexpr int kMaxThreads = 1024;  // far above any machine this runs on; 0 = all cores

inline const CLI::Validator& thread_count() {
  static const CLI::Range r(0, kMaxThreads);
  return r;
}
inline const CLI::Validator& sample_count() {
  static const CLI::Range r(1, 1 << 30);
  return r;
}
inline const CLI::Validator& path_depth() {
  static const CLI::Range r(1, 1024);
  return r;
}
// A positive, finite number of seconds, at most a year (CLI::Range lets NaN through).
inline const CLI::Validator& seconds() {
  static const CLI::Validator v(
      [](std::string& s) -> std::string {
        if (!core::is_decimal_number(s))  // also rejects hex, which std::stod reads
          return "expects a number of seconds, got '" + s.substr(0, 40) + (s.size() > 40 ? "...'" : "'");
        const double t = std::strtod(s.c_str(), nullptr);  // inf on overflow (std::stod throws)
        if (!std::isfinite(t) || !(t > 0.0) || t > 3.2e7) return "must be a finite number of seconds in (0, 3.2e7]";
        return std::string();
      },
      "SECONDS");
  return v;
}

// `--part K/N` (issue 17): part K of N, 1 <= K <= N <= kMaxParts. parse_part returns
// false for anything else (the validator's message names the form).
constexpr int kMaxParts = 1 << 20;
inline bool parse_part(const std::string& s, int& k, int& n) {
  const size_t slash = s.find('/');
  if (slash == std::string::npos) return false;
  const std::string a = s.substr(0, slash), b = s.substr(slash + 1);
  auto digits = [](const std::string& t) {
    return !t.empty() && t.size() <= 8 && t.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!digits(a) || !digits(b)) return false;
  k = std::stoi(a);
  n = std::stoi(b);
  return k >= 1 && k <= n && n <= kMaxParts;
}
inline const CLI::Validator& part_spec() {
  static const CLI::Validator v(
      [](std::string& s) -> std::string {
        int k = 0, n = 0;
        if (parse_part(s, k, n)) return std::string();
        return "expects K/N with 1 <= K <= N <= " + std::to_string(kMaxParts) + ", got '" + s.substr(0, 40) +
               (s.size() > 40 ? "...'" : "'");
      },
      "K/N");
  return v;
}

}  // namespace dp::apps
