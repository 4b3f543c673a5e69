#include "integrators/plane/plane_gather.h"

#include <algorithm>
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

Rgb plane_estimate_grid(const scene::HomogeneousMedium& med, const MediumPlane& pl, const PlaneHit& h, const Vec3& d,
                        float tr_c, PlaneFault fault) {
  const scene::DensityGrid& g = *med.density;
  const float dmax = g.max_value;
  if (!(dmax > 0.0f) || !(tr_c > 0.0f)) return Rgb::Zero();
  // pl.grid = [t0_i (n0), Tr_hat after each (n0), kept t1_j] (photon_plane.h).
  const size_t n0 = pl.grid_n0;
  const float* t0s = pl.grid.data();
  const float* v0s = t0s + n0;
  const float* t1s = v0s + n0;
  const size_t n1 = pl.grid.size() - 2 * n0;
  // Tr_hat(t0): the running product after the collisions before t0 (TransmittanceProfile::at).
  const size_t k = size_t(std::lower_bound(t0s, t0s + n0, float(h.t0)) - t0s);
  const double tr0 = k == 0 ? 1.0 : double(v0s[k - 1]);
  if (!(tr0 > 0.0)) return Rgb::Zero();
  const Eigen::Vector3d a1 = pl.a0.cast<double>() + h.t0 * pl.w0.cast<double>();
  const Eigen::Vector3d w1 = pl.w1.cast<double>();
  // Tr_hat(t0, t1): ratio tracking from a1 over the kept collisions before t1, each / c.
  double tr1 = 1.0;
  if (fault != PlaneFault::grid_no_w1_transmittance)
    for (size_t j = 0; j < n1 && double(t1s[j]) < h.t1; ++j) {
      const Vec3 x = (a1 + double(t1s[j]) * w1).cast<float>();
      const double c = fault == PlaneFault::grid_no_w1_roulette ? 1.0 : double(pl.grid_c);
      tr1 *= double(std::max(0.0f, 1.0f - g.lookup(x) / dmax)) / c;
      if (!(tr1 > 0.0)) return Rgb::Zero();
    }
  const Vec3 a1f = a1.cast<float>(), bf = (a1 + h.t1 * w1).cast<float>();
  const bool majorant = fault == PlaneFault::grid_sigma_s_majorant;
  const double da = majorant ? double(dmax) : double(g.lookup(a1f)), db = majorant ? double(dmax) : double(g.lookup(bf));
  if (!(da > 0.0) || !(db > 0.0)) return Rgb::Zero();
  const double p_s = fault == PlaneFault::no_scatter_probability ? 1.0 : double(pl.p_scatter);
  const double jac = fault == PlaneFault::no_det ? 1.0 : h.inv_det;
  const float rho = scene::HenyeyGreenstein(med.phase).eval(pl.w1, -d);
  const Rgbd sigma2 = (med.sigma_s * med.sigma_s).cast<double>();
  return (pl.beta.cast<double>() * sigma2 *
          (tr0 * da * tr1 * db * double(tr_c) * double(rho) * jac / (p_s * double(pl.q))))
      .cast<float>();
}

Rgb PlaneGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                        GatherCounters& counters) const {
  const Rgb beams = m_beam_gather.gather(ray, seg_len, medium, max_photon_depth, rng, counters);
  Rgbd sum = Rgbd::Zero();
  // A grid medium: the camera side's Tr from one ratio-tracking profile of the segment
  // (drawn after the beam part's; homogeneous media draw nothing here).
  thread_local scene::TransmittanceProfile profile;
  const scene::TransmittanceProfile* camera_tr = nullptr;
  if (m_scene.media()[size_t(medium)].heterogeneous() && max_photon_depth >= 2 && !m_planes.empty() &&
      seg_len > 0.0f) {
    profile.track(m_scene.media()[size_t(medium)], ray.o, ray.d, seg_len, rng);
    camera_tr = &profile;
  }
  for_each_plane_hit(m_scene, m_planes, ray, seg_len, medium, max_photon_depth, m_settings.fault, camera_tr, counters,
                     [&](const MediumPlane&, const PlaneHit&, const Rgb& v) { sum += v.cast<double>(); });
  return beams + (sum / double(m_paths)).cast<float>();
}

}  // namespace dp::integrators
