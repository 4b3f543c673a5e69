// Settings of gradient-domain MLT (`--integrator gdmlt`, Manzi et al. 2014 on the
// extended path space). Each key is read with its default and documentation in
// gdmlt_settings.cpp and written to the sidecar.
#pragma once

#include <cstdint>
#include <string>

#include "gradients/shift.h"
#include "integrators/settings.h"

namespace dp::integrators {

struct GdmltSettings {
  std::string kernel = "standard";  // gradient kernel: standard (4-neighbour); adaptive: not yet
  std::string shift = "manifold";   // T_1: manifold (Lehtinen 2013) | reconnection | identity
  float shift_threshold = 0.05f;    // roughness at or below it: glossy/specular
  bool mwgi = true;                 // multiple weighted gradient integrals (Eq. 6)
  double mwgi_threshold = 20;       // t of Eq. 6
  bool incmw = false;               // incremental manifold walk: not yet
  float alpha = 0.2f;               // primal weight in the target and in the Poisson solve
  std::string reconstruction = "l1";
  std::string mutations = "pss";    // pss (Kelemen); path: needs the path-space mutations
  double large_step_prob = 0.3;
  int64_t bootstrap = 100000;
  bool large_step_b = true;
  int chains = 0;                   // 0 = 4 per thread
  int rr_depth = 5;
  bool nee = true;
  int direct_spp = 0;               // direct pass (paths of <= 2 segments): spp; 0 = auto (see .cpp)
  // Not a --set key: tests' negative controls (a render with it must be rejected as biased).
  gradients::JacobianFault fault = gradients::JacobianFault::none;

  static GdmltSettings read(Settings& s);
};

}  // namespace dp::integrators
