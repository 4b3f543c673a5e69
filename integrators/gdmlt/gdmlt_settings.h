// Settings of gradient-domain MLT (`--integrator gdmlt`, Manzi et al. 2014 on the
// extended path space). Each key is read with its default and documentation in
// gdmlt_settings.cpp and written to the sidecar.
#pragma once

#include <cstdint>
#include <string>

#include "gradients/shift.h"
#include "kernels_adaptive/affinity.h"
#include "integrators/path_chains.h"
#include "integrators/settings.h"

namespace dp::integrators {

struct GdmltSettings {
  std::string kernel = "adaptive";  // gradient kernel: adaptive (Manzi 2014 Sec. 3.5) | standard (4-neighbour)
  int feature_spp = 4;              // primary rays per pixel of the feature pass (kernel=adaptive)
  kernels_adaptive::AffinityParams affinity;  // Sec. 5 defaults; window and neighbours are --set keys
  double symmetric_weight = 1.0;    // solve weight of each row of a symmetric pair (1: the paper)
  std::string shift = "manifold";   // T_1: manifold (Lehtinen 2013) | reconnection | identity
  float shift_threshold = 0.05f;    // roughness at or below it: glossy/specular
  bool mwgi = true;                 // multiple weighted gradient integrals (Eq. 6)
  double mwgi_threshold = 20;       // t of Eq. 6
  bool incmw = true;                // incremental manifold walk guided by screen-space AO (Sec. 3.4)
  double ao_threshold = 0.95;       // declare the next vertex specular where AO exceeds it (both sides)
  double ao_radius = 0.0075;        // AO ray length: fraction of the image size, projected (Sec. 5)
  int ao_rays = 16;                 // AO secondary rays per pixel
  float alpha = 0.2f;               // primal weight in the target and in the Poisson solve
  std::string reconstruction = "l1";
  std::string mutations = "pss";    // pss (Kelemen) | path (path-space mutations, gdmlt_path.h)
  PathMutationSettings path_mutations{"memlt"};  // mutations=path: the mutation set (memlt's)
  int candidates = 16384;           // mutations=path: seeder paths estimating b_g and seeding the chains
  double large_step_prob = 0.3;
  int64_t bootstrap = 100000;
  bool large_step_b = true;
  int chains = 0;                   // 0 = 4 per thread
  int rr_depth = 5;
  bool nee = true;
  int direct_spp = 0;               // direct pass (paths of <= 2 segments): spp; 0 = auto (see .cpp)
  // Not a --set key: tests' negative controls (a render with it must be rejected as biased).
  gradients::JacobianFault fault = gradients::JacobianFault::none;
  bool fault_symmetric_as_one = false;  // adaptive kernel: symmetric pairs splatted with weight 1, not 2

  static GdmltSettings read(Settings& s);
};

}  // namespace dp::integrators
