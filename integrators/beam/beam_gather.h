// The photon beam estimators of `beam` (Jarosz et al. 2011, "A comprehensive theory of
// volumetric radiance estimation using photon points and beams" (JZJ11), and
// "Progressive photon beams" (PPB); the primal Beam of Gruson et al. 2018, Sec. 5.2):
// the camera segment c + t w_c, t in [0, s], inside a medium against the photon beams
// a + v w_b, v in [0, l] (media_photons/photon_tracer.h) of the same medium and of
// depth <= the path-length budget.
//
// Why short beams are unbiased (photon_tracer.h stores them). In a light path the
// segment from a has throughput beta_a; the radiance it carries at a + v w_b is
// beta_a Tr(v) per emitted path (Eq. 2's tau on the light edge ab), so
//   sigma_s L_i(x, w_o) ~ 1/N sum_k int_0^{l_k} sigma_s rho_p(w_k, w_o) beta_k
//                                   Tr_k(v) / P_k(v) delta(x - b_k(v)) dv       (1)
// (the beam-photon form of JZJ11's Eq. 18 and Gruson et al.'s Eq. 5 with the light
// vertex b integrated along ab). The free flight from a, one of the three channels
// chosen uniformly (scene/media/free_flight.h), passes v < t_surf with probability
// P(v) = 1/3 sum_c exp(-sigma_t[c] v): the short beam covers v iff it passed, so
// E[1(v <= l) Tr(v) / P(v)] = Tr(v) per channel, also for chromatic sigma_t (Tr_c / P
// <= 3 stays bounded). A long beam (to the surface, weight Tr(v)) would be unbiased
// too; short beams are cheaper to query and give the photons' free flights for free.
// BeamFault::no_pass_probability drops the 1 / P(v) (biased low for chromatic media and
// wherever sigma_t > 0).
//
// The camera segment integrates L_m = int_0^s Tr_c(t) sigma_s L_i(c + t w_c, -w_c) dt.
// Blurring the delta in (1) with a kernel gives the two estimators:
//  * Beam-Beam 3D (`kernel: 3d`, Gruson et al. 2018, Sec. 5.2, Fig. 6c, the paper's
//    choice for beams, Sec. 6.1): delta -> K3, the uniform 3D kernel of radius r. The
//    double integral over (t, v) of Tr_c(t) K3(c + t w_c - b(v)) ... is estimated by one
//    v drawn uniformly on the part of the beam within r of the camera line and whose
//    projection onto it lies in [-r, s + r] (an interval: a cylinder and a slab; every
//    point within r of the segment is in it), pdf 1 / chord; the t integral is exact:
//    K3 x int Tr_c(t) dt over the camera chord within r of b(v), clipped to [0, s],
//    int_{t0}^{t1} e^{-sigma t} dt = (e^{-sigma t0} - e^{-sigma t1}) / sigma per channel:
//      L_m ~ 1/N sum_k beta_k Tr_k(v)/P_k(v) sigma_s rho_p(w_k, -w_c) K3 [int Tr_c] chord_k.
//    Unbiased for the 3D-blurred L_m (the same blurred quantity as `vpm` and `bre`
//    estimate); its bias is the blur's: O(r^2) in smooth regions, and near medium
//    boundaries up to half the kernel's mass lost (a kernel centred in a convex medium
//    keeps at least half of itself); consistent as r -> 0 (progressive radius with
//    dimension 3, volume_kernel.h).
//  * Beam x Beam 1D (`kernel: 1d`, JZJ11's Beam x Beam 1D estimator, the one PPB uses): delta blurred with a 1D
//    uniform kernel K1(u) = 1 / (2r) along the direction perpendicular to both lines; the
//    change of variables from the beam's position to (t_c, v_b, u) at the closest points
//    has Jacobian sin(theta), theta the angle between w_c and w_b, so
//      L_m ~ 1/N sum_k beta_k Tr_k(v_b)/P_k(v_b) sigma_s rho_p(w_k, -w_c) Tr_c(t_c) K1(u) / sin(theta)
//    over beams whose closest points lie in both segments at distance u <= r. Biased by
//    the 1D blur only (Tr and rho_p exact at the closest points): none in a field that is
//    uniform across the lines, but up to the whole kernel near a medium boundary (both
//    halves of the line across can leave a convex medium) and at segment ends (the
//    closest point must lie in both segments); its variance grows as 1 / sin(theta) for
//    near-parallel beams (the second moment diverges logarithmically: JZJ11's caveat).
//    Exactly parallel pairs (sin^2 < 1e-12: no closest point) are skipped and counted.
//    Progressive radius with dimension 1. Gruson et al. (Sec. 6.1) found no clear benefit
//    over 3D at equal time, and the radii shrink at different rates.
// The query is BeamBvh's: the beams' pieces within r of the segment (exact distance);
// each piece is estimated over its own range, so the sum over a beam's pieces is the
// beam's estimate (3D: one v per piece, uniform on the piece's part of the interval;
// 1D: the piece holding the closest point).
#pragma once

#include <vector>

#include "integrators/beam/beam_bvh.h"
#include "integrators/beam/beam_settings.h"
#include "integrators/media_photons/media_camera.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium.h"

namespace dp::integrators {

// The contribution (before 1/N) of the piece v in [v0, v1] of a beam (beam_bvh.h; the
// pieces of a beam partition [0, length]) to the camera segment c + t w_c, t in [0, s]
// (s finite) in medium `med` at radius r; `u` in [0, 1) draws the 3D kernel's beam point
// on the piece. Zero when the piece does not reach within r; in 1D, unless the closest
// point lies in the piece ([v0, v1), the last piece also at v1 = length). Counts
// parallel pairs (1D) in `counters`.
// The BVH's piece length for these beams at radius r (beam_bvh.h; measured choice in the
// .cpp).
float beam_piece_length(const scene::Scene& scene, const std::vector<MediumBeam>& beams, float r);
// Tr_b(v) / P(v) of a short beam at v ((1) above); Tr_b(v) alone with the planted
// BeamFault::no_pass_probability.
Rgb beam_point_weight(const scene::HomogeneousMedium& med, float v, BeamFault fault = BeamFault::none);
// The part [lo, hi] of the beam line a + v w, v in [v0, v1], within r of the camera line
// c + t w_c whose projection onto it lies in [-r, s + r] (an interval: a cylinder and a
// slab; every point within r of the segment is in it); false if empty. Beam-Beam 3D
// draws its beam point uniformly on it.
bool beam_tube_interval(const Vec3& a, const Vec3& w, double v0, double v1, const Vec3& c, const Vec3& w_c, double s,
                        double r, double& lo, double& hi);
// Grid media (`camera_tr` required): a delta-tracking free flight passes v with
// probability P(v) = Tr_b(v) exactly (grey sigma_t), so a short beam's point weight is 1;
// sigma_s is taken at the beam point (density x the medium's sigma_s), and the camera
// side's Tr from the segment's ratio-tracking profile (scene/media/grid_tracking.h:
// unbiased at every t and in its integral over the chord).
Rgb beam_beam_3d(const scene::HomogeneousMedium& med, const MediumBeam& beam, float v0, float v1, const Vec3& c,
                 const Vec3& w_c, float s, float r, float u, BeamFault fault = BeamFault::none,
                 const scene::TransmittanceProfile* camera_tr = nullptr);
Rgb beam_beam_1d(const scene::HomogeneousMedium& med, const MediumBeam& beam, float v0, float v1, const Vec3& c,
                 const Vec3& w_c, float s, float r, GatherCounters& counters, BeamFault fault = BeamFault::none,
                 const scene::TransmittanceProfile* camera_tr = nullptr);

class BeamGather final : public MediumGather {
 public:
  BeamGather(const scene::Scene& scene, const BeamSettings& settings, const BeamBvh& beams, float radius,
             int64_t light_paths)
      : m_scene(scene), m_settings(settings), m_beams(beams), m_radius(radius), m_paths(light_paths) {}
  Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
             GatherCounters& counters) const override;

 private:
  const scene::Scene& m_scene;
  const BeamSettings& m_settings;
  const BeamBvh& m_beams;
  float m_radius;
  int64_t m_paths;
};

}  // namespace dp::integrators
