// Settings of gradient-domain vertex connection and merging (`--integrator gvcm`, Sun et
// al. 2017). Each key is read with its default and documentation in gvcm_settings.cpp and
// written to the sidecar. max_depth comes from RenderOptions; `--spp` is the number of
// iterations (one light path and one camera path per pixel each).
#pragma once

#include <string>

#include "gradients/shift.h"
#include "integrators/settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_gvcm.cpp). C++ only.
struct GvcmFaults {
  bool mis_without_offset = false;  // gradient weight = the base's VCM weight (passive strategies left out)
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shifts
};

struct GvcmSettings {
  bool merging = true;        // mode: vcm (connections + merges) | bpt (connections only: no photons, no grid)
  float radius_scale = 1.0f;  // r_1 = radius_scale x the median pixel footprint at z_b (Sec. 6)
  float radius_alpha = 0.9f;  // per-iteration reduction r_i = r_1 i^((alpha - 1) / 2) (paper: 0.9)
  int rr_depth = 5;           // Russian roulette on each subpath after this many segments
  pathspace::MisHeuristic heuristic = pathspace::MisHeuristic::power;  // beta = 2 (Eq. 21-23) or balance
  float alpha = 0.3f;          // screened Poisson weight of the primal (paper's runs: 0.3)
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  std::string primal = "pairs";       // pairs (both pixels' pair estimates, as G-PT) | vcm
  bool manifold = true;               // walk specular chains (camera side b..c, photons' chains)
  GvcmFaults faults;                  // tests only

  static GvcmSettings read(Settings& s);
};

}  // namespace dp::integrators
