// Wall-clock timer on steady_clock (never clock(): it sums CPU time over threads).
#pragma once

#include <chrono>

namespace dp::core {

class Timer {
 public:
  Timer() : m_start(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }
  void reset() { m_start = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point m_start;
};

}  // namespace dp::core
