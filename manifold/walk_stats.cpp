#include "manifold/walk_stats.h"

namespace dp::manifold {

void WalkStats::merge(const WalkStats& o) {
  attempted += o.attempted;
  converged += o.converged;
  traces += o.traces;
  for (size_t k = 0; k < iterations.size(); ++k) iterations[k] += o.iterations[k];
  for (size_t k = 0; k < failures.size(); ++k) failures[k] += o.failures[k];
}

void WalkStats::flush(core::Stats& stats, const std::string& prefix) const {
  stats.add(prefix + ".walks", attempted);
  stats.add(prefix + ".converged", converged);
  stats.add(prefix + ".traces", traces);
  for (size_t k = 0; k < iterations.size(); ++k)
    if (iterations[k] > 0) stats.add(prefix + ".iterations." + std::to_string(k), iterations[k]);
  for (size_t k = 1; k < failures.size(); ++k)
    if (failures[k] > 0) stats.add(prefix + ".fail." + to_string(WalkStatus(k)), failures[k]);
}

double WalkStats::mean_iterations() const {
  int64_t n = 0, sum = 0;
  for (size_t k = 0; k < iterations.size(); ++k) {
    n += iterations[k];
    sum += int64_t(k) * iterations[k];
  }
  return n > 0 ? double(sum) / double(n) : 0.0;
}

}  // namespace dp::manifold
