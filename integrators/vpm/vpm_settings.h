// Settings of volumetric photon mapping (`--integrator vpm`): the shared keys of
// media_photons/media_photon_settings.h (radius_scale default 0.15% of the scene
// diagonal, Gruson et al. 2018, Sec. 6.1) plus `distance_samples`. Written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_vpm_bre.cpp). C++
// only: VpmSettings::read never sets them; the default leaves every image bit-identical.
enum class VpmFault : uint8_t {
  none,
  kernel_2d_norm,          // the 3D kernel normalized as a 2D one (1 / (pi r^2))
  no_transmittance,        // the gather point's Tr(c, d) left out (Eq. 5's tau(d, c))
  untruncated_pdf,         // the distance pdf without the truncation 1 / (1 - exp(-sigma_t s)) of Eq. 14
};

struct VpmSettings : MediaPhotonSettings {
  int distance_samples = 40;  // gather points per camera segment in a medium (Gruson et al. 2018: 40 per pixel)
  VpmFault fault = VpmFault::none;  // tests only

  static VpmSettings read(Settings& s);
  // The `distance_samples` setting (>= 1), shared with gvpm's gathers.
  static int read_distance_samples(Settings& s, int fallback);
};

}  // namespace dp::integrators
