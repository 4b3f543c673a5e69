// Reconnection of a shifted medium photon to its parent (G-VPM, Gruson et al. 2018,
// Sec. 4.3; docs/gvpm_plan.md step 4), for a parent that is itself a medium vertex a
// (phase function HG g, reached along unit direction w_in). The second building block of
// `gvpm`; surface and light parents are not here.
// In the volume measure (Eq. 4: G = 1 / t^2 without cosines at medium vertices) the edge
// a -> b and the vertex b contribute
//   f(a -> b) = rho_p(w_in, w) tau(a, b) G(a, b) sigma_s(b) = rho_p Tr(t) sigma_s / t^2,
// and the photon tracer (integrators/media_photons/photon_tracer.h) sampled b with
//   p(b | a) = p_phase(w_in, w) p_ff(t) / t^2   (direction x free-flight mixture, dV = t^2 dw dt),
// so its photon weight is beta_a f(a -> b) / p(b | a). The offset photon b' of a shift with
// Jacobian 1 in the volume measure (volume_photon_shift.h) reconnected to a weighs
//   beta_a f(a -> b') / p(b | a)                                     (Eq. 11, light side),
// and the offset light path's own density, for the MIS of Eq. 19, is p(b' | a).
// t = |b - a|, w = (b - a) / t; densities per unit volume, f per channel.
#pragma once

#include "core/math.h"
#include "scene/media/medium.h"

namespace dp::gradients {

struct MediumParent {
  Vec3 a{0, 0, 0};
  Vec3 w_in{0, 0, 1};  // unit direction the light travelled to reach a
};

// Deliberate defect for the tests (test_volume_photon_shift.cpp): f and p in solid angle
// times distance (no 1 / t^2), so the ratio misses t_b^2 / t_b'^2.
enum class ReconnectFault : uint8_t { none, no_volume_factor };

// p(b | a) per unit volume; 0 at b = a.
float photon_volume_pdf(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                        ReconnectFault fault = ReconnectFault::none);
// f(a -> b) per channel (see above); 0 at b = a.
Rgb photon_edge_throughput(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                           ReconnectFault fault = ReconnectFault::none);

}  // namespace dp::gradients
