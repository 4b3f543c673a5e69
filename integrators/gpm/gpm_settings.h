// Settings of gradient-domain photon mapping (`--integrator gpm`; G-PM as Sun et al. 2017,
// Sec. 7, implement it): the shared keys of photon_gradient_settings.h plus `primal`.
// Written to the sidecar. max_depth comes from RenderOptions; `--spp` is the number of
// iterations (one light path and one camera path per pixel each).
#pragma once

#include <string>

#include "gradients/shift.h"
#include "integrators/photon_gradient_settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_gpm.cpp). C++ only:
// GpmSettings::read never sets them.
struct GpmFaults {
  bool unit_area_ratio = false;     // the merging shift's light-side area factor reported as 1
  bool mis_without_offset = false;  // gradient weight 1: the passive (offset pixel's) strategy left out
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shifts
};

struct GpmSettings : PhotonGradientSettings {
  std::string primal = "pairs";  // pairs (both pixels' pair estimates, as G-PT) | ppm
  GpmFaults faults;              // tests only

  static GpmSettings read(Settings& s);
};

}  // namespace dp::integrators
