#include "integrators/plane/plane_gather.h"

#include <cmath>

#include "gradients/volume_plane_shift.h"
#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

bool plane_intersect(const Vec3& a0, const Vec3& w0, const Vec3& w1, const Vec3& c, const Vec3& d, PlaneHit& hit) {
  // c - a0 in float, as the renders before G-Plane (bit-identical images).
  return gradients::plane_ray_solve<double>(Eigen::Vector3d::Zero(), w0.cast<double>(), w1.cast<double>(),
                                            (c - a0).cast<double>(), d.cast<double>(), hit.t0, hit.t1, hit.w,
                                            hit.inv_det);
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

Rgb PlaneGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                        GatherCounters& counters) const {
  const Rgb beams = m_beam_gather.gather(ray, seg_len, medium, max_photon_depth, rng, counters);
  Rgbd sum = Rgbd::Zero();
  for_each_plane_hit(m_scene, m_planes, ray, seg_len, medium, max_photon_depth, m_settings.fault, counters,
                     [&](const MediumPlane&, const PlaneHit&, const Rgb& v) { sum += v.cast<double>(); });
  return beams + (sum / double(m_paths)).cast<float>();
}

}  // namespace dp::integrators
