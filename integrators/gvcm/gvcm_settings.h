// Settings of gradient-domain vertex connection and merging (`--integrator gvcm`, Sun et
// al. 2017): the shared keys of photon_gradient_settings.h plus `mode` and `primal`.
// Written to the sidecar. max_depth comes from RenderOptions; `--spp` is the number of
// iterations (one light path and one camera path per pixel each).
#pragma once

#include <string>

#include "gradients/shift.h"
#include "integrators/photon_gradient_settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_gvcm.cpp). C++ only.
struct GvcmFaults {
  bool mis_without_offset = false;  // gradient weight = the base's VCM weight (passive strategies left out)
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shifts
};

struct GvcmSettings : PhotonGradientSettings {
  bool merging = true;           // mode: vcm (connections + merges) | bpt (connections only: no photons, no grid)
  std::string primal = "pairs";  // pairs (both pixels' pair estimates, as G-PT) | vcm
  float roughness_threshold = 0.01f;  // no merge below this roughness (Sun et al. 2017, Sec. 7: 0.01)
  bool adaptive_kernel = true;   // r_t = 0.5^(10 tau(z_(t-1))) r_(t-1) along the camera subpath (Sec. 6)
  GvcmFaults faults;             // tests only

  static GvcmSettings read(Settings& s);
};

}  // namespace dp::integrators
