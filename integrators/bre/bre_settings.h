// Settings of the beam radiance estimate (`--integrator bre`): the shared keys of
// media_photons/media_photon_settings.h with radius_scale's default 0.10% of the scene
// diagonal (Gruson et al. 2018, Sec. 6.1), and the kernel: `2d` (Jarosz et al. 2008: a 2D
// kernel across the beam, photons projecting into the segment) or `3d` (the paper's
// Point-Beam 3D, Sec. 5.1: each photon's 3D kernel integrated along the camera segment,
// the primal of `gbre`). Written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_vpm_bre.cpp). C++
// only: BreSettings::read never sets them; the default leaves every image bit-identical.
enum class BreFault : uint8_t {
  none,
  kernel_3d_norm,     // the kernel normalized as the other dimension's (2D: 3 / (4 pi r^3); 3D: 1 / (pi r^2))
  no_transmittance,   // Tr(c, t_k) along the beam left out
};

struct BreSettings : MediaPhotonSettings {
  int kernel_dim = 2;               // 2 or 3 (`kernel`: 2d | 3d)
  BreFault fault = BreFault::none;  // tests only
  static BreSettings read(Settings& s);
};

}  // namespace dp::integrators
