// Settings of gradient-domain volumetric photon mapping (`--integrator gvpm`): `vpm`'s
// (media_photons/media_photon_settings.h: photons, radius_scale 0.15% of the scene
// diagonal, radius_alpha 0.7, rr_depth; distance_samples 40) plus the gradient-domain
// keys: the screened Poisson weight alpha (Gruson et al. 2018, Sec. 6.1: lambda = 0.2),
// the reconstruction shown (L1, the paper's) and the photon shift (mixed, Eq. 16, or
// the simple shift). Written to the sidecar.
// `gbre` (G-BRE, Sec. 5.1) is the same integrator with beam gathers (GvpmGather::beam):
// `bre`'s keys (radius_scale 0.10%, no distance_samples) and the same gradient keys.
// `gbeam` (G-Beam, Sec. 5.2; GvpmGather::beams): `beam`'s keys (photons 20000 light
// paths, radius_scale 0.10%) and the same gradient keys.
// `gplane` (G-Plane, Sec. 5.3; GvpmGather::planes): `plane`'s keys (photons 20000 light
// paths, radius_scale 0.10% for the beam part, plane_piece_scale 1/64) and the gradient
// keys but mixed_shift (planes have no kernel to mix in).
#pragma once

#include <string>

#include "gradients/volume_photon_chain.h"
#include "integrators/media_photons/media_photon_settings.h"

namespace dp::integrators {

// Deliberate defects the tests must reject (test_gvpm*.cpp). C++ only: read() never sets
// them; the default leaves every image bit-identical.
enum class GvpmFault : uint8_t {
  none,
  untruncated_offset_pdf,  // the offset's gather density without Eq. 14's truncation 1 / (1 - exp(-sigma_t s'))
  mis_weight_one,          // the pair's MIS weight 1 on both sides (Eq. 19 left out)
  chord_as_diameter,       // gbre: the gather density 1 / (2r) instead of 1 / |chord| (the chord's clipping and
                           // its photon's distance from the ray ignored)
  beam_chord_ignored,      // gbeam: the beam photon not divided by its density 1 / |beam chord|
  plane_eq18_jacobian,     // gplane: the shift's Jacobian with Eq. 18's printed t-factors (volume_plane_shift.h)
};

// How the primary ray's segments are gathered: `gvpm`'s gather points (distance samples,
// 3D point queries) or `gbre`'s Point-Beam 3D (every photon within r of the segment, its
// gather point drawn uniformly on its chord).
// `gbeam` (G-Beam, Sec. 5.2): the primary ray's segments against photon beams, Beam-Beam
// 3D (a photon drawn uniformly on each beam's chord near the segment, then a gather point
// uniformly on the camera chord around it), shifted as gbre's.
// `gplane` (G-Plane, Sec. 5.3): the primary ray's segments against photon planes (the 0D
// plane estimate, plane_gather.h), each hit shifted by the rotation of
// gradients/volume_plane_shift.h; the beams not from scattering events go unshifted to
// `direct`.
enum class GvpmGather : uint8_t { points, beam, beams, planes };

struct GvpmSettings : MediaPhotonSettings {
  int distance_samples = 40;          // gather points per camera segment in a medium (as vpm)
  float alpha = 0.2f;                 // screened Poisson weight of the primal (Sec. 6.1: lambda = 0.2)
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  bool mixed = true;                  // mixed photon shift (Eq. 16); false: the simple shift b + (d' - d)
  GvpmGather gather = GvpmGather::points;
  double plane_piece_scale = 1.0 / 64.0;  // gplane: as plane's `plane_piece_scale` (plane_settings.h)
  // Photons behind purely specular chains (gradients/volume_photon_chain.h; Sec. 4.3, 6):
  bool manifold = true;           // reconnect them by a manifold walk (false: the shift fails, counted)
  int manifold_iterations = 5;    // walk iterations (Sec. 6: 5)
  bool manifold_relaxed = true;   // Sec. 6's relaxed acceptance: the walk's end need only fall in the offset kernel
  GvpmFault fault = GvpmFault::none;  // tests only
  gradients::ReconnectFault reconnect_fault = gradients::ReconnectFault::none;  // tests only
  gradients::ChainFault chain_fault = gradients::ChainFault::none;              // tests only

  static GvpmSettings read(Settings& s);       // gvpm
  static GvpmSettings read_gbre(Settings& s);  // gbre
  static GvpmSettings read_gbeam(Settings& s); // gbeam
  static GvpmSettings read_gplane(Settings& s); // gplane
  const char* name() const {
    switch (gather) {
      case GvpmGather::beam: return "gbre";
      case GvpmGather::beams: return "gbeam";
      case GvpmGather::planes: return "gplane";
      default: return "gvpm";
    }
  }

 private:
  void read_gradient_keys(Settings& s, bool photon_shift = true);  // photon_shift: also mixed_shift
};

}  // namespace dp::integrators
