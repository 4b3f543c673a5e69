// G-Plane (Gruson et al. 2018, Sec. 5.3): GvpmTracer's gathers and shifts of photon planes.
// A term is one visible hit (t0, t1, w) of a primary segment with a plane (a0; w0, w1),
// its base value x = plane_estimate / N (plane/plane_gather.h; the sample is the raster
// position and w1, p(x) = p_phase(w1) P_pass(t1) per plane). Its offset into neighbour j:
//   the primary ray through the same sub-pixel position of j (GvpmTracer::offsets), segment
//   k of the base mapped to segment k; w' = w (fails where that segment is missing, in
//   another medium or not longer than w); b' = d'; the plane rotated about its light
//   segment to hold d' (gradients/volume_plane_shift.h; fails for a degenerate plane or
//   where a1' leaves the segment's kept range [t0_begin, t0_end]); a shadow ray a1' -> d'.
//   The phase at a1 keeps its angle, so p_phase(w1') = p_phase(w1) and, with the Jacobian
//   |dw1'/dw1| = |det'| / |det| t1 / t1',
//     R = p(Tx) |T'| / p(x) = P_pass(t1') / P_pass(t1) |dw1'/dw1|,
//     f(Tx) |T'| / p(x) = [f(Tx) / p(Tx)] R = plane_estimate(offset) / N x R,
//   the pair weighted by Eq. 19's balance heuristic 1 / (1 + R) (PairSplats::mis_pair).
//   An offset of zero value (occluded, Tr 0) is a failed shift (the T_0 fallback), as
//   G-VPM's: the check is symmetric, so the weights of both directions still sum to 1.
#include <cmath>

#include "gradients/volume_plane_shift.h"
#include "integrators/gvpm/gvpm_tracer.h"
#include "scene/media/free_flight.h"

namespace dp::integrators {

void GvpmTracer::gather_planes(const GvpmSegment& seg, int k, GvpmScratch& sc, GvpmCounters& counters) const {
  const double inv_n = 1.0 / double(m_paths);
  for_each_plane_hit(m_scene, *m_planes, seg.ray, seg.len, seg.medium, m_max_depth - 1, PlaneFault::none, nullptr,
                     counters.camera.gather, [&](const MediumPlane& pl, const PlaneHit& h, const Rgb& v) {
                       ++counters.photons_gathered;
                       ++counters.gather_points;
                       sc.plane_terms.push_back({k, &pl, h, seg.beta * v * float(inv_n)});
                     });
}

void GvpmTracer::plane_offsets(int nb, int px, int py, GvpmScratch& sc, GvpmCounters& counters) const {
  using V = Eigen::Vector3d;
  const bool weight_one = m_settings.fault == GvpmFault::mis_weight_one;
  const gradients::PlaneShiftFault jac_fault = m_settings.fault == GvpmFault::plane_eq18_jacobian
                                                   ? gradients::PlaneShiftFault::paper_eq18
                                                   : gradients::PlaneShiftFault::none;
  const double inv_n = 1.0 / double(m_paths);
  for (const GvpmPlaneTerm& term : sc.plane_terms) {
    const GvpmSegment& base = sc.base[size_t(term.segment)];
    const MediumPlane& pl = *term.plane;
    const PlaneHit& h = term.hit;
    const scene::HomogeneousMedium& med = m_scene.media()[size_t(base.medium)];
    ++counters.shifts;
    Rgbd off_v = Rgbd::Zero();
    double R = 0.0;
    bool ok = false;
    const GvpmSegment* off = nullptr;
    if (size_t(term.segment) >= sc.offset.size()) ++counters.fail_segment_missing;
    else if (sc.offset[size_t(term.segment)].medium != base.medium) ++counters.fail_medium;
    else if (!(h.w < double(sc.offset[size_t(term.segment)].len))) ++counters.fail_distance;
    else off = &sc.offset[size_t(term.segment)];
    gradients::PlaneRotation<double> rot;
    if (off) {
      const V d_off = off->ray.o.cast<double>() + h.w * off->ray.d.cast<double>();
      const V a0 = pl.a0.cast<double>(), w0 = pl.w0.cast<double>(), w1 = pl.w1.cast<double>();
      if (!gradients::rotate_plane_to(a0, w0, w1, d_off, rot)) {
        ++counters.fail_plane_degenerate;
      } else if (!(rot.t0 >= double(pl.t0_begin)) || !(rot.t0 <= double(pl.t0_end))) {
        ++counters.fail_plane_segment;
      } else if (m_scene.occluded((a0 + rot.t0 * w0).cast<float>(), d_off.cast<float>())) {
        ++counters.fail_occluded;
      } else {
        MediumPlane pl_off = pl;
        pl_off.w1 = rot.w1.cast<float>();
        PlaneHit h_off;
        h_off.t0 = rot.t0;
        h_off.t1 = rot.t1;
        h_off.w = h.w;
        h_off.inv_det = 1.0 / gradients::plane_det(w0, rot.w1, V(off->ray.d.cast<double>()));
        const double jac = gradients::plane_shift_jacobian(w0, w1, V(base.ray.d.cast<double>()), h.t0, h.t1, rot.w1,
                                                           V(off->ray.d.cast<double>()), rot.t0, rot.t1, jac_fault);
        R = jac * double(scene::free_flight_pass_probability(med, float(rot.t1))) /
            double(scene::free_flight_pass_probability(med, float(h.t1)));
        const Rgb est = off->beta * plane_estimate(med, pl_off, h_off, off->ray.d);
        off_v = est.cast<double>() * (inv_n * R);
        ok = !off_v.isZero() && R > 0.0 && std::isfinite(R);
        ++(ok ? counters.plane_rotations : counters.fail_zero);
      }
    }
    const bool paired =
        sc.splats.mis_pair(nb, px, py, term.value.cast<double>(), 1.0, ok, off_v, 1.0, R, 1.0, weight_one);
    ++(paired ? counters.pairs_shifted : counters.pairs_fallback);
  }
}

}  // namespace dp::integrators
