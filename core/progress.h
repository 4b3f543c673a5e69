// Progress bar with ETA on stderr. Silent when stderr is not a terminal or when
// constructed quiet. Thread-safe `advance`.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace dp::core {

class Progress {
 public:
  Progress(std::string label, int64_t total, bool quiet);
  ~Progress();
  void advance(int64_t n = 1);
  // For time-budgeted renders: fraction of the budget elapsed drives the bar.
  void set_fraction(double f);
  void finish();

 private:
  void draw(double fraction);
  std::string m_label;
  int64_t m_total;
  bool m_enabled;
  std::atomic<int64_t> m_done{0};
  std::chrono::steady_clock::time_point m_start;
  std::chrono::steady_clock::time_point m_last_draw;
  std::mutex m_mutex;
  bool m_finished = false;
};

}  // namespace dp::core
