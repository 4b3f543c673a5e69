#include "integrators/plane/plane_gather.h"

#include <cmath>

#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

bool plane_intersect(const Vec3& a0, const Vec3& w0, const Vec3& w1, const Vec3& c, const Vec3& d, PlaneHit& hit) {
  using V = Eigen::Vector3d;
  const V e0 = w0.cast<double>(), e1 = w1.cast<double>(), dd = d.cast<double>();
  // t0 e0 + t1 e1 - w d = c - a0; det[e0, e1, -d] = e0 . (d x e1) (Cramer's rule).
  const V p = dd.cross(e1);
  const double det = e0.dot(p);
  if (!(std::abs(det) > 1e-12)) return false;
  const double inv = 1.0 / det;
  const V s = (c - a0).cast<double>();
  const V q = s.cross(e0);
  hit.t0 = s.dot(p) * inv;
  hit.t1 = dd.dot(q) * inv;
  hit.w = e1.dot(q) * inv;
  hit.inv_det = std::abs(inv);
  return true;
}

Rgb plane_estimate(const scene::HomogeneousMedium& med, const MediumPlane& pl, const PlaneHit& h, const Vec3& d,
                   PlaneFault fault) {
  const Rgb tr0 = scene::transmittance(med, float(h.t0)), tr1 = scene::transmittance(med, float(h.t1));
  const Rgb tr_c = scene::transmittance(med, float(h.w));
  const float pass =
      fault == PlaneFault::no_pass_probability ? 1.0f : scene::free_flight_pass_probability(med, float(h.t1));
  if (!(pass > 0.0f)) return Rgb::Zero();
  const double p_s = fault == PlaneFault::no_scatter_probability ? 1.0 : double(pl.p_scatter);
  const double jac = fault == PlaneFault::no_det ? 1.0 : h.inv_det;
  const float rho = scene::HenyeyGreenstein(med.phase).eval(pl.w1, -d);
  const Rgb w = pl.beta * tr0 * med.sigma_s * tr1 * med.sigma_s * tr_c / pass;
  return (w.cast<double>() * (double(rho) * jac / (p_s * double(pl.q)))).cast<float>();
}

namespace {
// v in the piece's half-open range [lo, hi) (closed at the plane's end): each point of a
// plane belongs to exactly one piece.
bool in_piece(double v, float lo, float hi, float end) {
  return v >= double(lo) && (v < double(hi) || (!(hi < end) && v <= double(hi)));
}
}  // namespace

Rgb PlaneGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                        GatherCounters& counters) const {
  const Rgb beams = m_beam_gather.gather(ray, seg_len, medium, max_photon_depth, rng, counters);
  // A plane's points have depth >= 2 (a segment, then its scattering event's direction).
  if (max_photon_depth < 2 || m_planes.empty() || !(seg_len > 0.0f)) return beams;
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  if (is_black(med.sigma_s)) return beams;
  const float s = m_planes.clip(ray.o, ray.d, seg_len);
  if (!(s > 0.0f)) return beams;
  const PlaneFault fault = m_settings.fault;
  Rgbd sum = Rgbd::Zero();
  m_planes.query_segment(ray.o, ray.d, s, [&](const MediumPlane& pl, const PlaneBvh::Piece& pc) {
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
    if (!in_piece(h.t0, pc.u0, pc.u1, pl.t0_end) || !in_piece(h.t1, pc.v0, pc.v1, pl.t1_end) || !(h.w >= 0.0) ||
        !(h.w <= double(s)))
      return;
    ++counters.intersections;
    const Vec3 a1 = (pl.a0.cast<double>() + h.t0 * pl.w0.cast<double>()).cast<float>();
    const Vec3 b = (ray.o.cast<double>() + h.w * ray.d.cast<double>()).cast<float>();
    if (fault != PlaneFault::no_occlusion && m_scene.occluded(a1, b)) {
      ++counters.occluded;
      return;
    }
    const Rgb v = plane_estimate(med, pl, h, ray.d, fault);
    if (is_black(v)) return;
    ++counters.photons;
    sum += v.cast<double>();
  });
  return beams + (sum / double(m_paths)).cast<float>();
}

}  // namespace dp::integrators
