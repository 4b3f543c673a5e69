// The photon plane estimate of `plane` (Bitterli & Jarosz 2017, "Beyond points and beams:
// higher-dimensional photon samples for volumetric light transport"; the primal Plane of
// Gruson et al. 2018, Sec. 5.3, Plane-Beam 0D, Fig. 6f): a camera segment c + w d, w in
// [0, W], inside a medium against the photon planes a0 + t0 w0 + t1 w1 of the same medium
// (media_photons/photon_plane.h), plus `beam`'s Beam-Beam 3D on the beams that do not
// start at a scattering event.
//
// Derivation (volume measure; Gruson et al. 2018, Eqs. 2-5). The camera segment needs
//   L_m = int_0^W Tr_c(w) sigma_s int rho(w1, -d) L(x_w, w1) dw1 dw,   x_w = c + w d.
// Split L(x, w1) by the last light vertex's predecessor along the straight line into x:
//  (P) a medium scattering event a1 = x - t1 w1 with no surface in between:
//      L_P(x, w1) = int_0^inf Tr(t1) V(a1, x) sigma_s int rho(w', w1) L(a1, w') dw' dt1;
//  (B) a light or surface vertex, or an index-matched boundary crossed on the way (the
//      light tracer restarts its segment there): exactly the light carried by the short
//      beams that do not start at a scattering event (MediumBeam::after_scatter false),
//      estimated by beam_beam_3d (beam/beam_gather.h; the 3D blur, progressive radius).
//      The beams from scattering events carry (P) and are left out of the beam BVH.
// For (P) write a1 = x_w - t1 w1 as int dV(a1) delta(a1 + t1 w1 - x_w) and replace
// int dV(a1) int dw' L(a1, w') h(a1, w') by the long-beam identity over the light
// segments, E[sum_k beta_k int_0^{T_k} Tr(t0) h(a0_k + t0 w0_k, w0_k) dt0] (the photons'
// Eq. 5 form, photon_tracer.h; T_k the segment's distance to its surface):
//   L_m^P = E sum_k beta_a0 int dw1 int dt0 dt1 dw Tr(t0) sigma_s rho(w0, w1) Tr(t1)
//           sigma_s rho(w1, -d) Tr_c(w) V delta(a0 + t0 w0 + t1 w1 - c - w d).
// The delta is 3D in (t0, t1, w): int delta(M (t0, t1, w) - (c - a0)) = 1 / |det M|,
// M = [w0, w1, -d], at the unique solution (Moller & Trumbore 1997's system), so
//   L_m^P = E sum_k beta_a0 int dw1 Tr(t0) sigma_s rho(w0,w1) Tr(t1) sigma_s rho(w1,-d)
//           Tr_c(w) V / |det[w0, w1, d]|        (0 <= t0 <= T0, t1 >= 0, 0 <= w <= W).
// The dw1 integral takes the phase sample at the event (rho / p = 1, HG), drawn only when
// the flight scattered before T0 and survived roulette (P_s q, photon_plane.h), and t1 is
// covered when t1 <= D (probability P_pass(t1)): one plane hit contributes
//   beta_a0 Tr(t0) sigma_s Tr(t1)/P_pass(t1) sigma_s rho(w1, -d) Tr_c(w) / (|det| P_s q) / N
// per channel (chromatic sigma_t: every Tr and P is the mixture's). No kernel: unbiased
// (beyond the clip of unbounded media). V: one shadow ray a1(t0) -> x_w, blocked by any
// surface (an index-matched one too: that light is (B)'s).
//
// Grid media (medium.h: sigma(x) = density(x) x the medium's coefficients, sigma_t grey,
// majorant mu = sigma_t x max density over the grid's box, 0 outside it). The (P)/(B)
// split and the identity above hold as written with sigma_s -> sigma_s(a1), sigma_s(x_w)
// and every Tr the grid's exp(-int sigma_t) along its own line:
//   L_m^P = E sum_k beta_a0 int dw1 Tr_k(t0) sigma_s(a1) rho(w0,w1) Tr(a1 -> b)
//           sigma_s(b) rho(w1,-d) Tr_c(w) V / |det[w0, w1, d]|,  a1 = a0 + t0 w0, b = a1 + t1 w1.
// (The light paths are delta tracked: their beta_a0 at the start of each medium segment
// has the expectation the long-beam identity needs, grid_tracking.h.) What has no closed
// form: P_s = 1 - Tr(t_surf) (a plane's production), Tr_k(t0), Tr(a1 -> b) (the line
// moves with t0) and Tr_c(w). So a grid plane (media_photons/photon_plane.h,
// record_plane_grid) is built from its own random numbers, independent of each other
// given the light segment, and each factor is replaced by an unbiased estimate:
//  (G1) production: every medium segment makes a plane with probability P_rec = 1 -
//       exp(-mu L) (closed form; L its length in the box), weight 1 / P_rec: E[1{kept} /
//       P_rec] = 1 whatever the segment. A point with t0 outside the box has sigma_s(a1)
//       = 0, so the t0 range is the box's part of [0, t_surf). No roulette (q = 1).
//  (G2) w1 ~ the phase function around w0: rho(w0, w1) / p(w1) = 1 (HG; one phase per
//       medium), so the dw1 integral is this one sample.
//  (G3) Tr_k(t0): a ratio-tracking profile along w0 (scene::TransmittanceProfile's
//       estimator): for each t0 it is ratio tracking stopped at t0, E = Tr_k(t0) (Novak et
//       al. 2014; the product over tentative collisions of rate mu of 1 - sigma_t / mu).
//       Where the product reaches 0 the plane ends in t0: beyond, every estimate is 0.
//  (G4) Tr(a1 -> b) at t1, with its extent: one tentative-collision process t1_j of rate mu
//       along the w1 axis, shared by every t0, each collision kept with probability c = 1
//       - min density / max density (does not depend on t0), the plane ending at the
//       first one not kept (t1_end: the analogue of D). For a fixed t0 with N collisions
//       before t1 and f_j = 1 - sigma_t(a1 + t1_j w1) / mu,
//         E[1{t1 < t1_end} prod_{j<=N} f_j / c] = E[prod_j 1{u_j < c} f_j / c] = E[prod_j f_j]
//       = Tr(a1 -> b): ratio tracking (unbiased for any t0, the process not depending on
//       it). It needs c > 0 wherever f_j != 0 for a point that matters: both a1 and b are
//       in the box (else sigma_s = 0), the box is convex, so every a1 + t1_j w1 with t1_j
//       < t1 is in it, where f_j <= c (trilinear density >= the smallest node value); with
//       c = 0 (a constant grid) every f_j is 0 and the plane ends at the first collision
//       (an exponential D of rate mu with weight 1 = Tr / P_pass: the homogeneous case).
//       The extent is bounded by the box (per axis over the t0 range).
//  (G5) Tr_c(w): one ratio-tracking profile of the camera segment (as `beam`, drawn in
//       PlaneGather::gather from the camera path's stream), unbiased at every w.
//  (G6) sigma_s(a1), sigma_s(b): the density looked up at the two points (exact).
// Given the light path and the camera segment, (G1)-(G5) use disjoint random numbers,
// so the estimates are independent and the expectation of their product is the product
// of their expectations: each hit's value
//   beta_a0 Tr_hat0(t0) sigma_s(a1) Tr_hat1(t0,t1) sigma_s(b) rho(w1,-d) Tr_hat_c(w) / (|det| P_rec)
// has, conditioned on the segments, the expectation of the integrand of L_m^P at that
// (t0, t1, w) times the indicator the plane reaches it, whose 1 / P_rec and (G4)
// coverage are already folded in; summing over hits and integrating against the delta as
// above gives L_m^P. V, 1 / |det| and the 1 / N are as in the homogeneous case, and the
// (B) part is `beam`'s grid estimator (beam_gather.h). Nothing is clamped or truncated
// beyond the homogeneous form's clip of unbounded media (a grid medium is bounded by its
// box): the grid plane estimator is unbiased. Planted defects (test_plane_grid.cpp):
// PlaneFault::grid_no_camera_transmittance, grid_sigma_s_majorant, grid_no_w1_transmittance,
// grid_no_w1_roulette.
#pragma once

#include "integrators/beam/beam_gather.h"
#include "integrators/plane/plane_bvh.h"
#include "integrators/plane/plane_settings.h"

namespace dp::integrators {

struct PlaneHit {
  double t0 = 0, t1 = 0, w = 0;  // a0 + t0 w0 + t1 w1 = c + w d
  double inv_det = 0;            // 1 / |det[w0, w1, d]|
};

// Solves the 3x3 system (Moller & Trumbore's triple products, double); false when the
// segment's direction is parallel to the plane (|det| < 1e-12).
bool plane_intersect(const Vec3& a0, const Vec3& w0, const Vec3& w1, const Vec3& c, const Vec3& d, PlaneHit& hit);

// One hit's contribution before 1 / N and before visibility (see the header comment).
Rgb plane_estimate(const scene::HomogeneousMedium& med, const MediumPlane& pl, const PlaneHit& h, const Vec3& d,
                   PlaneFault fault = PlaneFault::none);
// The same in a grid medium (see "Grid media" above) with the camera side's Tr_c(w) estimate.
Rgb plane_estimate_grid(const scene::HomogeneousMedium& med, const MediumPlane& pl, const PlaneHit& h, const Vec3& d,
                        float tr_c, PlaneFault fault = PlaneFault::none);

// v in the piece's half-open range [lo, hi) (closed at the plane's end): each point of a
// plane belongs to exactly one piece.
inline bool in_plane_piece(double v, float lo, float hi, float end) {
  return v >= double(lo) && (v < double(hi) || (!(hi < end) && v <= double(hi)));
}

// Every visible plane hit of the camera segment (ray.o + w ray.d, w in [0, seg_len], inside
// medium `medium`, planes of depth <= max_photon_depth): fn(plane, hit, value) with value
// plane_estimate's (before 1 / N). Counts plane_tests, parallel, intersections, occluded,
// depth_skipped and photons (the hits passed to fn) in `counters`. A grid medium needs
// `camera_tr`, the segment's ratio-tracking profile (no hit without it).
template <class Fn>
void for_each_plane_hit(const scene::Scene& scene, const PlaneBvh& planes, const Ray& ray, float seg_len, int medium,
                        int max_photon_depth, PlaneFault fault, const scene::TransmittanceProfile* camera_tr,
                        GatherCounters& counters, Fn&& fn) {
  // A plane's points have depth >= 2 (a segment, then its scattering event's direction).
  if (max_photon_depth < 2 || planes.empty() || !(seg_len > 0.0f)) return;
  const scene::HomogeneousMedium& med = scene.media()[size_t(medium)];
  if (is_black(med.sigma_s)) return;
  const bool grid = med.heterogeneous();
  if (grid && !camera_tr) return;
  const float s = planes.clip(ray.o, ray.d, seg_len);
  if (!(s > 0.0f)) return;
  planes.query_segment(ray.o, ray.d, s, [&](const MediumPlane& pl, const PlaneBvh::Piece& pc) {
    if (pl.medium != medium) return;
    if (pl.depth > max_photon_depth) {
      ++counters.depth_skipped;
      return;
    }
    ++counters.plane_tests;
    PlaneHit h;
    if (!plane_intersect(pl.a0, pl.w0, pl.w1, ray.o, ray.d, h)) {
      ++counters.parallel;
      return;
    }
    if (!in_plane_piece(h.t0, pc.u0, pc.u1, pl.t0_end) || !in_plane_piece(h.t1, pc.v0, pc.v1, pl.t1_end) ||
        !(h.w >= 0.0) || !(h.w <= double(s)))
      return;
    ++counters.intersections;
    const Vec3 a1 = (pl.a0.cast<double>() + h.t0 * pl.w0.cast<double>()).cast<float>();
    const Vec3 b = (ray.o.cast<double>() + h.w * ray.d.cast<double>()).cast<float>();
    if (fault != PlaneFault::no_occlusion && scene.occluded(a1, b)) {
      ++counters.occluded;
      return;
    }
    const Rgb v = !grid ? plane_estimate(med, pl, h, ray.d, fault)
                        : plane_estimate_grid(med, pl, h, ray.d,
                                              fault == PlaneFault::grid_no_camera_transmittance
                                                  ? 1.0f
                                                  : camera_tr->at(float(h.w)),
                                              fault);
    if (is_black(v)) return;
    ++counters.photons;
    fn(pl, h, v);
  });
}

class PlaneGather final : public MediumGather {
 public:
  // `beams`: the beams not starting at a scattering event (or all with the planted
  // PlaneFault::beams_after_scatter), gathered as `beam` does with `beam_settings`.
  PlaneGather(const scene::Scene& scene, const PlaneSettings& settings, const BeamSettings& beam_settings,
              const BeamBvh& beams, const PlaneBvh& planes, float radius, int64_t light_paths)
      : m_scene(scene),
        m_settings(settings),
        m_beam_gather(scene, beam_settings, beams, radius, light_paths),
        m_planes(planes),
        m_paths(light_paths) {}
  Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
             GatherCounters& counters) const override;

 private:
  const scene::Scene& m_scene;
  const PlaneSettings& m_settings;
  BeamGather m_beam_gather;
  const PlaneBvh& m_planes;
  int64_t m_paths;
};

}  // namespace dp::integrators
