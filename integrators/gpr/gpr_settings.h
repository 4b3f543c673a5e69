// Settings of gradient-domain path reusing (`--integrator gpr`, Bauszat et al. 2017,
// Sec. 3.2-3.3). The reuse itself (tile, shift, NEE, Russian roulette depth) is `pr`'s
// (PrSettings); on top: the proportional Russian roulette on base paths and the
// reconstruction keys of `gpt`. Each key is read with its default and documentation in
// gpr_settings.cpp and written back into the sidecar.
#pragma once

#include <string>

#include "integrators/pr/pr_settings.h"
#include "integrators/settings.h"

namespace dp::integrators {

// Deliberate defects that the tests' statistical checks must reject (test_gpr*.cpp). C++
// only: GprSettings::read never sets them, no scene key or --set reaches them, and the
// default leaves every image bit-identical.
struct GprFaults {
  // q = min(1, lum / delta) without the floor q_min (Sec. 3.3): a base path of zero
  // contribution is never reused, although its shifted paths may carry light.
  bool rr_without_floor = false;
  // Tiles not extended by the one-pixel border (Sec. 3.2, Fig. 4): a pair whose right /
  // lower pixel lies in the next tile gets no estimate.
  bool no_border = false;
};

struct GprSettings {
  PrSettings reuse;                 // tile, rr_depth, nee, shift_threshold (+ PrFaults)
  double rr_delta = 0.1;            // base-path RR: q = max(min(1, lum / delta), q_min); 0 = off
  double rr_min = 0.1;              // q_min > 0 keeps the estimator unbiased (Sec. 3.3)
  bool jitter = true;               // random tile-grid offset per iteration (Sec. 3.3)
  bool early_out = true;            // drop a base's suffix that cannot carry light (Sec. 3.3)
  float alpha = 0.2f;               // screened Poisson weight of the primal
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  GprFaults faults;                 // tests only, never read from settings (see GprFaults)

  static GprSettings read(Settings& s);
};

}  // namespace dp::integrators
