// Settings of gradient-domain volumetric photon mapping (`--integrator gvpm`): `vpm`'s
// (media_photons/media_photon_settings.h: photons, radius_scale 0.15% of the scene
// diagonal, radius_alpha 0.7, rr_depth; distance_samples 40) plus the gradient-domain
// keys: the screened Poisson weight alpha (Gruson et al. 2018, Sec. 6.1: lambda = 0.2),
// the reconstruction shown (L1, the paper's) and the photon shift (mixed, Eq. 16, or
// the simple shift). Written to the sidecar.
#pragma once

#include <string>

#include "gradients/volume_photon_reconnect.h"
#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests must reject (test_gvpm*.cpp). C++ only: read() never sets
// them; the default leaves every image bit-identical.
enum class GvpmFault : uint8_t {
  none,
  untruncated_offset_pdf,  // the offset's gather density without Eq. 14's truncation 1 / (1 - exp(-sigma_t s'))
  mis_weight_one,          // the pair's MIS weight 1 on both sides (Eq. 19 left out)
};

struct GvpmSettings : MediaPhotonSettings {
  int distance_samples = 40;          // gather points per camera segment in a medium (as vpm)
  float alpha = 0.2f;                 // screened Poisson weight of the primal (Sec. 6.1: lambda = 0.2)
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  bool mixed = true;                  // mixed photon shift (Eq. 16); false: the simple shift b + (d' - d)
  GvpmFault fault = GvpmFault::none;  // tests only
  gradients::ReconnectFault reconnect_fault = gradients::ReconnectFault::none;  // tests only

  static GvpmSettings read(Settings& s);
};

}  // namespace dp::integrators
