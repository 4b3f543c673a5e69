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

// v in the piece's half-open range [lo, hi) (closed at the plane's end): each point of a
// plane belongs to exactly one piece.
inline bool in_plane_piece(double v, float lo, float hi, float end) {
  return v >= double(lo) && (v < double(hi) || (!(hi < end) && v <= double(hi)));
}

// Every visible plane hit of the camera segment (ray.o + w ray.d, w in [0, seg_len], inside
// medium `medium`, planes of depth <= max_photon_depth): fn(plane, hit, value) with value
// plane_estimate's (before 1 / N). Counts plane_tests, parallel, intersections, occluded,
// depth_skipped and photons (the hits passed to fn) in `counters`.
template <class Fn>
void for_each_plane_hit(const scene::Scene& scene, const PlaneBvh& planes, const Ray& ray, float seg_len, int medium,
                        int max_photon_depth, PlaneFault fault, GatherCounters& counters, Fn&& fn) {
  // A plane's points have depth >= 2 (a segment, then its scattering event's direction).
  if (max_photon_depth < 2 || planes.empty() || !(seg_len > 0.0f)) return;
  const scene::HomogeneousMedium& med = scene.media()[size_t(medium)];
  if (is_black(med.sigma_s)) return;
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
    const Rgb v = plane_estimate(med, pl, h, ray.d, fault);
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
