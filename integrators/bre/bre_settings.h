// Settings of the beam radiance estimate (`--integrator bre`): the shared keys of
// media_photons/media_photon_settings.h with radius_scale's default 0.10% of the scene
// diagonal (Gruson et al. 2018, Sec. 6.1). Written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_vpm_bre.cpp). C++
// only: BreSettings::read never sets them; the default leaves every image bit-identical.
enum class BreFault : uint8_t {
  none,
  kernel_3d_norm,     // the 2D kernel normalized as a 3D one (3 / (4 pi r^3))
  no_transmittance,   // Tr(c, t_k) along the beam left out
};

struct BreSettings : MediaPhotonSettings {
  BreFault fault = BreFault::none;  // tests only
  static BreSettings read(Settings& s);
};

}  // namespace dp::integrators
