// Settings of the primal photon beams (`--integrator beam`): the shared keys of
// media_photons/media_photon_settings.h with `photons` defaulting to 20000 light paths per
// iteration (Gruson et al. 2018, Sec. 6.1, deposit 20e3 beams per iteration; here every
// medium segment of a light path is a beam, so 20000 paths give at least as many beams
// where the light enters a medium) and radius_scale to 0.10% of the scene diagonal
// (Sec. 6.1), plus `kernel`: 3d (Beam-Beam 3D, the paper's choice, Sec. 6.1) or 1d (the
// Beam x Beam 1D estimate of Jarosz et al. 2011). Written to the sidecar.
#pragma once

#include <cstdint>
#include <string>

#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

enum class BeamKernel : uint8_t { k3d, k1d };

// Deliberate defects the tests must reject (test_beam.cpp). C++ only: BeamSettings::read
// never sets them; the default leaves every image bit-identical.
enum class BeamFault : uint8_t {
  none,
  bvh_unpadded,       // the BVH's node and leaf boxes not grown by r (misses beams near a box)
  no_chord_pdf,       // 3D: the sampled beam point not divided by its pdf 1 / chord
  no_pass_probability,  // short beams weighted Tr(v) as long beams (no 1 / P(free flight > v))
  no_camera_transmittance,  // 3D: the chord length instead of int Tr_c; 1D: Tr_c(t_c) left out
  no_sin_theta,       // 1D: the 1 / sin(theta) of the line-line Jacobian left out
};

struct BeamSettings : MediaPhotonSettings {
  BeamKernel kernel = BeamKernel::k3d;
  BeamFault fault = BeamFault::none;  // tests only

  BeamSettings() {
    photons = 20000;
    radius_scale = 0.001;
  }
  int kernel_dim() const { return kernel == BeamKernel::k3d ? 3 : 1; }
  std::string kernel_name() const { return kernel == BeamKernel::k3d ? "3d" : "1d"; }
  static BeamSettings read(Settings& s);
};

}  // namespace dp::integrators
