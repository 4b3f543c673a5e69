// Settings of the primal photon planes (`--integrator plane`): the shared keys of
// media_photons/media_photon_settings.h with `photons` defaulting to 20000 light paths per
// iteration (Gruson et al. 2018, Sec. 6.1: 20e3 beams and planes per iteration; here each
// medium scattering event of a light path makes a plane) and radius_scale to 0.10% of the
// scene diagonal (the Beam-Beam 3D part only; planes have no kernel), plus
// `plane_piece_scale`: the planes' BVH pieces are at least this fraction of the scene
// diagonal on a side (plane_bvh.h). Written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests must reject (test_plane.cpp, test_plane_render.cpp,
// test_plane_grid.cpp). C++
// only: never read from settings; the default leaves every image bit-identical.
enum class PlaneFault : uint8_t {
  none,
  no_det,                  // the 1 / |det[w0, w1, d]| of the 3x3 delta left out
  no_scatter_probability,  // the 1 / P_s of the plane's production left out
  no_occlusion,            // no shadow ray from a1(t0) to the plane point
  no_pass_probability,     // Tr(t1) without the 1 / P_pass(t1) of the short extent D
  beams_after_scatter,     // the beam part also gathers beams that start at a scattering event (counted twice)
  // Grid media (test_plane_grid.cpp):
  grid_no_camera_transmittance,  // the camera side's ratio-tracked Tr_c taken as 1
  grid_sigma_s_majorant,         // sigma_s of the grid's maximum density at a1 and b, not the density there
  grid_no_w1_transmittance,      // the ratio product along w1 (Tr from a1 to b) taken as 1
  grid_no_w1_roulette,           // the factors along w1 not divided by their survival probability c
};

struct PlaneSettings : MediaPhotonSettings {
  double piece_scale = 1.0 / 64.0;
  PlaneFault fault = PlaneFault::none;  // tests only

  PlaneSettings() {
    photons = 20000;
    radius_scale = 0.001;
  }
  static PlaneSettings read(Settings& s);
};

}  // namespace dp::integrators
