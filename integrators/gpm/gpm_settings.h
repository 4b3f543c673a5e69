// Settings of gradient-domain photon mapping (`--integrator gpm`; G-PM as Sun et al. 2017,
// Sec. 7, implement it). Each key is read with its default and documentation in
// gpm_settings.cpp and written to the sidecar. max_depth comes from RenderOptions;
// `--spp` is the number of iterations (one light path and one camera path per pixel each).
#pragma once

#include <string>

#include "gradients/shift.h"
#include "integrators/settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_gpm.cpp). C++ only:
// GpmSettings::read never sets them.
struct GpmFaults {
  bool unit_area_ratio = false;     // the merging shift's light-side area factor reported as 1
  bool mis_without_offset = false;  // gradient weight 1: the passive (offset pixel's) strategy left out
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shifts
};

struct GpmSettings {
  float radius_scale = 1.0f;   // r_1 = radius_scale x the pixel footprint at z_b (Sun 2017, Sec. 6)
  float radius_alpha = 0.9f;   // per-iteration reduction r_i = r_1 i^((alpha - 1) / 2) (paper: 0.9)
  int rr_depth = 5;            // Russian roulette on each subpath after this many segments
  bool power = true;           // gradient MIS: power heuristic beta = 2 (Eq. 23) or balance (beta = 1)
  float alpha = 0.3f;          // screened Poisson weight of the primal (paper's runs: 0.3)
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  std::string primal = "pairs";       // pairs (both pixels' pair estimates, as G-PT) | ppm
  bool manifold = true;               // walk the photon's specular chain to z_b^off (Eq. 19-20)
  GpmFaults faults;                   // tests only

  static GpmSettings read(Settings& s);
};

}  // namespace dp::integrators
