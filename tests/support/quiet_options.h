// Render options of the statistical tests: a quiet 2-thread render of `spp` samples per
// pixel (or mutations per pixel) with a fixed seed.
#pragma once

#include <cstdint>

#include "integrators/integrator.h"

namespace dp::test {

inline integrators::RenderOptions quiet_options(int spp, uint64_t seed, int max_depth) {
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = max_depth;
  opt.quiet = true;
  return opt;
}

}  // namespace dp::test
