// Equiangular next-event estimation in homogeneous media (Kulla & Fajardo 2012, Sec. 4) and
// its MIS with volpath's free-flight NEE and phase sampling.
//
// A medium vertex x = o + t d on a camera-path segment, with a light connection x -> y, is
// made by three techniques; in the measure dt dw at x their densities are
//   free flight + NEE:           p1 = p_ff(t) L(w)   (L: NEE's solid-angle density of y from x)
//   free flight + phase:         p2 = p_ff(t) P(w)   (P: the phase function, = its value for HG)
//   light point + equiangular:   p3 = p_e(t | y) q(y) r^2 / |cos_y|
// (q: the area density of y, drawn once per segment by sample_direct from o; r = |y - x|),
// each weighted by the power heuristic p_i^2 / (p1^2 + p2^2 + p3^2). Divided by p_ff(t):
//   w_1 = L^2 / (L^2 + P^2 + R^2),  w_2 = P^2 / (...),  w_3 = R^2 / (...),
//   R = p3 / p_ff(t) (equiangular_ratio).
// Dirac lights have no w integral and no phase hit: p1 = p_ff(t), p3 = p_e(t | y), so
// w_1 = 1 / (1 + R^2), w_3 = R^2 / (1 + R^2) with R = p_e / p_ff.
// The equiangular estimate is beta Tr(t) sigma_s rho_p(d, w) Tr(x -> y) Le |cos_y| / r^2
// / (p_e(t) q(y)) w_3 (Gruson et al. 2018, Eqs. 2-4: the medium vertex's sigma_s rho_p
// and a geometry term without a cosine at x).
// Grid media (scene/media/grid_tracking.h): delta tracking's p_ff(t) = sigma_t(x) Tr(t) has no
// closed form, but the weights only need to be a partition of unity over the techniques
// for each path (Veach 1997, Sec. 9.2), so all three use the same deterministic stand-in
// sigma_t(x) exp(-tau_hat(o, x)) (pathspace/bidir_media.h, as bdpt's grid MIS). The
// contributions stay unbiased: delta tracking's albedo weight for the free-flight ones,
// Tr(t) by ratio tracking and sigma_s(x) = density(x) sigma_s for the equiangular one.
// Lights at infinity are never drawn by it (p3 = 0: their MIS is unchanged).
#include <cmath>

#include "integrators/path/path_tracer.h"  // power_heuristic
#include "integrators/volpath/volpath_tracer.h"
#include "pathspace/bidir_media.h"
#include "scene/media/equiangular.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

namespace {
// R = p3 / p_ff for an area light (header comment): p_e q(y) r^2 / (|cos_y| p_ff); 0 where
// equiangular sampling cannot make the connection.
float area_ratio(float pe, float p_ff, float q, float r2, float cos_y) {
  if (!(q > 0.0f) || !(cos_y > 0.0f)) return 0.0f;
  const float R = pe / p_ff * q * r2 / cos_y;
  return std::isfinite(R) ? R : 0.0f;
}
}  // namespace

float VolpathTracer::flight_pdf(int medium, const Vec3& o, const Vec3& d, float t) const {
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  if (!med.heterogeneous()) return scene::free_flight_pdf(med, t);
  return pathspace::end_factor(m_scene, medium, t, pathspace::Span::between(o, o + t * d), true);
}

float VolpathTracer::equiangular_ratio(const FlightSegment& f, const scene::Emitter& emitter, float pmf,
                                       const Vec3& y, const Vec3& n) const {
  if (!f.active || !(f.pdf > 0.0f) || emitter.is_infinite()) return 0.0f;
  const scene::Equiangular eq = scene::equiangular_setup(f.o, f.d, f.t_max, y);
  const float pe = scene::equiangular_pdf(eq, f.t_max, f.t);
  if (!(pe > 0.0f)) return 0.0f;
  if (emitter.is_delta()) return pe / f.pdf;
  const Vec3 w = y - (f.o + f.t * f.d);
  const float r2 = w.squaredNorm();
  return area_ratio(pe, f.pdf, pmf * emitter.pdf_area_direct(f.o, y, n), r2, std::abs(n.dot(w)) / std::sqrt(r2));
}

Rgb VolpathTracer::next_event_equiangular(const Ray& ray, float t_max, int medium, core::Rng& rng,
                                          VolpathCounters& c) const {
  const float u_light = rng.uniform(), u_t = rng.uniform();
  const Vec2 u = rng.uniform2();
  float pmf;
  const scene::Emitter* emitter = m_scene.sample_emitter(u_light, pmf);
  if (!emitter || emitter->is_infinite()) {
    ++c.equiangular_skipped;
    return Rgb::Zero();
  }
  const bool delta = emitter->is_delta();
  const scene::DirectSample dy = emitter->sample_direct(ray.o, u);  // y: drawn from o, before t
  const scene::Equiangular eq = scene::equiangular_setup(ray.o, ray.d, t_max, dy.p);
  if ((!delta && !(dy.pdf_area > 0.0f)) || !eq.ok) {
    ++c.equiangular_skipped;
    return Rgb::Zero();
  }
  ++c.equiangular_samples;
  const float t = scene::equiangular_sample(eq, t_max, u_t);
  const float pe = scene::equiangular_pdf(eq, t_max, t);
  if (!(pe > 0.0f)) return Rgb::Zero();
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  const FlightSegment f{true, ray.o, ray.d, t_max, t, flight_pdf(medium, ray.o, ray.d, t)};
  const Vec3 x = ray.at(t);
  const scene::HenyeyGreenstein phase(med.phase);
  Rgb value;  // Le G / (light density), without the phase function
  Vec3 wi;
  float dist, w, rho;  // rho: the phase function's value, = its pdf (HG)
  if (delta) {
    const scene::DirectSample ds = emitter->sample_direct(x, u);
    if (!(ds.pdf > 0.0f) || is_black(ds.radiance)) return Rgb::Zero();
    wi = ds.wi;
    dist = ds.dist;
    value = ds.radiance / pmf;
    rho = phase.eval(ray.d, wi);
    w = f.pdf > 0.0f ? power_heuristic(pe / f.pdf, 1.0f, 0.0f) : 1.0f;
  } else {
    const Vec3 d = dy.p - x;
    const float r2 = d.squaredNorm();
    dist = std::sqrt(r2);
    wi = d / dist;
    const float cos_y = -dy.n.dot(wi);
    if (!(cos_y > 0.0f) || !(r2 > 0.0f)) return Rgb::Zero();
    scene::SurfacePoint sp;
    sp.p = dy.p;
    sp.ng = dy.n;
    const Rgb Le = emitter->eval(sp, -wi);
    const float q = pmf * emitter->pdf_area_direct(ray.o, dy.p, dy.n);
    if (is_black(Le) || !(q > 0.0f)) return Rgb::Zero();
    value = Le * (cos_y / (r2 * q));
    rho = phase.eval(ray.d, wi);
    // p_e and q are this sample's own: equiangular_ratio's terms without recomputing them.
    const float L = pmf * emitter->pdf_direct(x, dy.p, dy.n, wi);
    w = f.pdf > 0.0f ? power_heuristic(area_ratio(pe, f.pdf, q, r2, cos_y), L, rho) : 1.0f;
  }
  if (m_settings.fault == VolpathFault::equiangular_without_mis) w = 1.0f;
  if (!(rho > 0.0f) || !(w > 0.0f)) return Rgb::Zero();
  ++c.shadow_rays;
  Ray r;
  r.o = x;
  r.d = wi;
  r.tmin = 0.0f;
  r.tmax = std::max(0.0f, dist - 2.0f * scene::Scene::epsilon_at(dy.p));
  int m = medium;
  Rgb tr;
  scene::SurfaceHit blocker;
  if (march(r, m, &dy.p, rng, c, tr, blocker) != MarchEnd::reached || is_black(tr)) {
    ++c.equiangular_occluded;
    return Rgb::Zero();
  }
  if (!med.heterogeneous()) return scene::transmittance(med, t) * med.sigma_s * tr * value * (rho * w / pe);
  const Rgb tr_t = scene::transmittance_grid(med, ray.o, ray.d, t, rng);  // ratio tracking
  return tr_t * (med.density->lookup(x) * med.sigma_s) * tr * value * (rho * w / pe);
}

}  // namespace dp::integrators
