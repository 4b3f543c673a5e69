// Manifold-walk statistics in plain integer counters (one per thread, no locking),
// merged and flushed into core::Stats at the end of a render under "<prefix>.*":
// walks, converged, traces, iterations.<k> (converged walks by iteration count),
// fail.<cause> (WalkStatus names).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/stats.h"
#include "manifold/chain.h"

namespace dp::manifold {

struct WalkStats {
  static constexpr int kIterationBins = 33;  // 0..31, last bin = 32 or more
  int64_t attempted = 0;
  int64_t converged = 0;
  int64_t traces = 0;  // chain re-traces (each costs n ray casts)
  std::array<int64_t, kIterationBins> iterations{};
  std::array<int64_t, kWalkStatusCount> failures{};

  void record(WalkStatus st, int iters) {
    ++attempted;
    if (st == WalkStatus::ok) {
      ++converged;
      ++iterations[size_t(std::min(iters, kIterationBins - 1))];
    } else {
      ++failures[size_t(st)];
    }
  }
  void merge(const WalkStats& o);
  void flush(core::Stats& stats, const std::string& prefix = "manifold") const;
  double mean_iterations() const;
};

}  // namespace dp::manifold
