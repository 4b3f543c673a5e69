// One share of an estimate that is a mean over independent samples (the bootstrap's b,
// the path seeder's b, GD-MLT's E[factor]), for renders split into parts (issue 17):
// part k of n holds the samples of the blocks of kBlock samples with block % n == k, so
// the n shares hold every sample once and sum/n over their totals is the whole mean.
#pragma once

#include <cstdint>

namespace dp::mcmc {

struct SampleShare {
  double sum = 0;       // sum of the samples' values (a non-finite sample counts 0)
  int64_t n = 0;        // samples
  int64_t invalid = 0;  // non-finite samples among them (dropped)
};

// Whether sample i belongs to part `part` of `parts` (blocks of `block` samples).
inline bool owns_sample(int64_t i, int64_t block, int part, int parts) {
  return parts <= 1 || (i / block) % parts == part;
}

}  // namespace dp::mcmc
