// Light tracing in volpath (setting light_tracing): a third technique for the paths MNEE
// makes, ... -> v -> x -> s_1 .. s_m -> y (s_i Dirac vertices on glass, y on an area light,
// v the camera or the camera-path vertex before the anchor x).
//
// Why. MNEE's estimate F(X) / p_L carries D = d w_0 / dA(y), which grows without bound
// at a caustic's folds, and its MIS with BSDF/phase sampling (p_B = p_x P D) bounds it
// only where p_B exceeds p_L = 1 / (light area): for a light of a few millimetres that is
// at D ~ 1e5-1e6. The caustic's pixels, and everything the caustic lights again, are then
// heavy-tailed (most renders a little low, rare ones far too bright). Light tracing samples
// the same paths from the light: y (p_pos), a direction (p_dir), the Dirac lobes (their
// selection probabilities P'), free flight along the chain, and lands on x with a density
// proportional to D, so the power heuristic over all three (volpath_mnee.h, mnee_mis)
// hands it the paths near the folds. bdpt joins light and camera subpaths the same way
// and has no such tails.
//
// Per camera sample one light path is traced until its first vertex x that is not a Dirac
// vertex (a medium scatter or a non-Dirac surface), after at least one Dirac vertex. x is
// joined to the camera (splatted: Veach 1997, Sec. 10.3.3, one light path per camera
// sample, splats scaled by pixel count / light paths) and to every medium and non-Dirac
// surface vertex v of the camera path (added to the sample), as bdpt's connections are.
// The densities, over the camera path's density of x drawn from v (link(): v's direction
// density / d^2, times |cos| at a surface x, times free flight's density of x along the
// segment; from the camera Camera::pdf_direction over the whole image), in p_L's units:
//   MNEE     p_L(y)
//   BSDF     p_B = p_x(w_0) prod P_i D
//   light    p_T = p_pos(y) p_dir(y -> s_m) prod P'_i F G / |cos_y| / p_cam(x | v)
// with G the generalized geometry term (D |cos_x| at a surface x; D in a medium), F free
// flight's probabilities along the chain (passing every segment; at a medium x its density
// of scattering there) and P'_i = P_i (a dielectric's Fresnel selection is the same from
// either side). MNEE and BSDF sampling count p_T wherever a joinable vertex v precedes x
// (MneeAnchor::lt: not after a Dirac sample), and a light path counts only chains that MNEE
// returns for (x, y), so the three weights sum to one on every path (and the paths MNEE
// misses keep their weight 1 on the BSDF side, as before).
//
// Scope: area lights (Scene::sample_emitter, as bdpt), homogeneous media, chains of at
// most mnee_max_chain Dirac vertices within max_depth (v's depth + 2 + m). Off by default:
// with a large light (the fogged test box) MNEE has no tails to bound and the light paths
// raised the variance of the image mean 1.2-1.8x (bench/RESULTS.md).
#include <algorithm>
#include <cmath>

#include "integrators/volpath/volpath_mnee_chain.h"
#include "integrators/volpath/volpath_tracer.h"
#include "pathspace/bidir_light.h"
#include "pathspace/bidir_subpath.h"
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

using scene::SurfaceHit;

void VolpathTracer::set_light_tracing() {
  m_light_tracing = m_settings.light_tracing && m_mnee && m_max_depth >= 3;
  for (const auto& med : m_scene.media())
    if (med.heterogeneous()) m_light_tracing = false;
}

VolpathTracer::CameraVertex VolpathTracer::camera_vertex() const {
  CameraVertex v;
  v.kind = CameraVertex::Kind::camera;
  v.at.p = m_scene.camera().position();
  v.at.medium = m_camera_medium;
  return v;
}

bool VolpathTracer::link(const CameraVertex& v, const MneeAnchor& x, core::Rng& rng, VolpathCounters& c, double& pdf,
                         Rgb& f_v, Rgb& tr) const {
  if (v.kind == CameraVertex::Kind::none) return false;
  const Vec3 xp = x.position();
  Vec3 w = xp - v.p();  // v -> x
  const float d = w.norm();
  if (!(d > 0.0f)) return false;
  w /= d;
  // v's side: its direction density toward x and its scattering value.
  float pdf_v = 0.0f;
  if (v.kind == CameraVertex::Kind::camera) {
    pdf_v = m_scene.camera().pdf_direction(w);
    f_v = Rgb::Constant(pdf_v);
  } else if (v.kind == CameraVertex::Kind::medium) {
    const scene::HenyeyGreenstein phase(m_scene.media()[size_t(v.at.medium)].phase);
    pdf_v = phase.pdf(v.at.d_in, w);
    f_v = Rgb::Constant(phase.eval(v.at.d_in, w));
  } else {
    const Vec3 wo = v.at.hit.shading.to_local(w);
    if (!pathspace::consistent_side(v.at.hit, w, wo.z())) return false;
    f_v = v.at.hit.bsdf->eval_pdf(pathspace::radiance_context(v.at.hit), v.at.wi_local, wo, pdf_v) * abs_cos_theta(wo);
  }
  if (!(pdf_v > 0.0f) || is_black(f_v)) return false;
  // The segment, marched from x (free flight's density of a scatter at a medium x).
  Ray r;
  if (x.surface) {
    r = m_scene.spawn_segment(x.hit, v.p());
  } else {
    r.o = xp;
    r.d = -w;
    r.tmin = 0.0f;
    r.tmax = std::max(0.0f, d - 2.0f * scene::Scene::epsilon_at(v.p()));
  }
  int medium = x.medium;
  double flight = 1.0;
  SurfaceHit blocker;
  if (march(r, medium, &v.p(), rng, c, tr, blocker, &flight, !x.surface) != MarchEnd::reached || is_black(tr))
    return false;
  pdf = double(pdf_v) / (double(d) * double(d)) * flight;
  if (x.surface) pdf *= std::abs(double(w.dot(x.hit.ng.normalized())));
  return pdf > 0.0 && std::isfinite(pdf);
}

double VolpathTracer::camera_pdf(const CameraVertex& v, const MneeAnchor& x, core::Rng& rng,
                                 VolpathCounters& c) const {
  double pdf = 0.0;
  Rgb f_v, tr;
  return link(v, x, rng, c, pdf, f_v, tr) ? pdf : 0.0;
}

double VolpathTracer::light_trace_density(const MneeAnchor& x, const scene::Emitter& e, const Vec3& y,
                                          const Vec3& n_y, const Vec3& s_m, double factors, double G) const {
  if (!x.lt || e.kind() != scene::EmitterKind::area) return 0.0;
  pathspace::BidirVertex y0;  // as pathspace::light_subpath draws it
  y0.kind = pathspace::BidirKind::light;
  y0.emitter = &e;
  y0.sp.p = y;
  y0.sp.ng = n_y.normalized();
  y0.sp.shading = Frame::from_normal(y0.sp.ng);
  const Vec3 w = (s_m - y).normalized();
  const double cos_y = std::abs(double(w.dot(y0.sp.ng)));
  const double p_dir = double(pathspace::light_pdf_dir(y0, w));
  if (!(cos_y > 0.0) || !(p_dir > 0.0)) return 0.0;
  const double p = double(pathspace::light_pdf_pos(m_scene, y0)) * p_dir * factors * G / cos_y;
  return std::isfinite(p) ? p : 0.0;
}

bool VolpathTracer::trace_light(core::Rng& rng, VolpathCounters& c, LightEnd& out) const {
  out = LightEnd{};
  ++c.light_paths;
  Ray ray;
  Rgb beta;
  pathspace::BidirVertex y0;
  if (!pathspace::emit_light_ray(m_scene, rng, ray, beta, &y0) || y0.emitter->kind() != scene::EmitterKind::area)
    return false;
  const int max_chain = std::min(m_settings.mnee_max_chain, m_max_depth - 2);
  std::array<Vec3, kMaxMneeChain> verts{};  // light first
  uint32_t reflect = 0;                     // bit j: the j-th vertex from the light reflects
  int m = 0;
  SurfaceHit h;
  bool found = m_scene.intersect(ray, h);
  // The light's medium is that of the near side of the first surface (as bdpt's walks).
  int medium = found ? scene::medium_toward(h, -ray.d, m_camera_medium, m_camera_medium) : m_camera_medium;
  for (int crossings = 0;;) {
    if (medium >= 0) {
      const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
      const float u_channel = rng.uniform(), u_distance = rng.uniform();
      const scene::FreeFlightSample ff = scene::sample_free_flight(med, found ? h.t : kInfinity, u_channel, u_distance);
      beta *= ff.weight;
      if (ff.scattered) {  // x in the medium
        out.p = ray.at(ff.t);
        break;
      }
    }
    if (!found || !h.bsdf || is_black(beta)) return false;
    if (scene::is_index_matched(h)) {
      if (++crossings > kMaxNullCrossings) return false;
      medium = scene::medium_toward(h, ray.d, medium, m_camera_medium);
      ray = m_scene.continue_ray(h, ray.d);
      found = m_scene.intersect(ray, h);
      continue;
    }
    if (!h.bsdf->is_purely_delta()) {  // x on a surface
      out.surface = true;
      out.hit = h;
      out.p = h.p;
      break;
    }
    if (m == max_chain) return false;
    const Vec3 wi = h.shading.to_local(-ray.d);
    if (!pathspace::consistent_side(h, -ray.d, wi.z())) return false;
    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = h.bsdf->sample(scene::BsdfContext{h.uv, scene::TransportMode::importance}, wi, u_lobe, u);
    if (!bs || is_black(bs->weight)) return false;
    const bool reflects = bs->lobe == scene::kDeltaReflection;
    if (!reflects && !(bs->lobe == scene::kDeltaTransmission && bs->eta != 1.0f)) return false;  // not MNEE's
    const Vec3 wo = h.shading.to_world(bs->wo);
    if (!pathspace::consistent_side(h, wo, bs->wo.z())) return false;
    if (reflects) reflect |= 1u << m;
    verts[size_t(m++)] = h.p;
    beta *= bs->weight;
    medium = scene::medium_toward(h, wo, medium, m_camera_medium);
    ray = m_scene.continue_ray(h, wo);
    found = m_scene.intersect(ray, h);
  }
  if (m == 0 || is_black(beta)) return false;  // lit directly: NEE's
  ++c.light_chains;
  out.d_in = ray.d;
  out.medium = medium;
  out.beta = beta;
  out.chain.m = m;
  for (int i = 0; i < m; ++i) {  // MNEE's order: s_1 next to x
    out.chain.verts[size_t(i)] = verts[size_t(m - 1 - i)];
    if (((reflect >> (m - 1 - i)) & 1u) != 0) out.chain.reflect_mask |= 1u << i;
  }
  out.emitter = y0.emitter;
  out.y = y0.sp.p;
  out.n_y = y0.sp.ng;
  out.ok = true;
  return true;
}

Rgb VolpathTracer::connect_light(const LightEnd& light, const CameraVertex& v, core::Rng& rng,
                                 VolpathCounters& c) const {
  if (!light.ok || v.kind == CameraVertex::Kind::none || v.at.depth + 2 + light.chain.m > m_max_depth)
    return Rgb::Zero();
  ++c.light_links;
  const Vec3 to_v = (v.p() - light.p).normalized();
  // x as the camera path would meet it coming from v (MNEE's anchor, depth v.at.depth + 1).
  MneeAnchor x;
  Rgb f_x;
  if (!light.surface) {
    x = MneeAnchor::in_medium(light.p, -to_v, light.medium, v.at.depth + 1);
    f_x = Rgb::Constant(scene::HenyeyGreenstein(m_scene.media()[size_t(light.medium)].phase).eval(light.d_in, to_v));
  } else {
    const SurfaceHit& h = light.hit;
    const Vec3 wi = h.shading.to_local(-light.d_in), wo = h.shading.to_local(to_v);
    if (pathspace::consistent_side(h, to_v, wo.z()))
      f_x = h.bsdf->eval(scene::BsdfContext{h.uv, scene::TransportMode::importance}, wi, wo) * abs_cos_theta(wo);
    else
      f_x = Rgb::Zero();
    x = MneeAnchor::at_surface(h, wo, scene::medium_toward(h, to_v, light.medium, m_camera_medium), v.at.depth + 1);
  }
  x.lt = true;
  Rgb f_v, tr;
  double cam_pdf = 0.0;
  if (is_black(f_x) || !link(v, x, rng, c, cam_pdf, f_v, tr)) {
    ++c.light_blocked;
    return Rgb::Zero();
  }
  // The MIS weight: MNEE must return this very chain from x to y (volpath_mnee.h).
  MneeConnection X;
  const double p_trace = mnee_find(x, light.y, light.n_y, light.chain, rng, c, X) ? trace_over(X, cam_pdf) : 0.0;
  if (!(p_trace > 0.0)) {
    ++c.light_unmatched;
    return Rgb::Zero();
  }
  const double w = m_settings.fault == VolpathFault::light_tracing_without_mis ? 1.0
                                                                             : mnee_mis(p_trace, X.p_light, X.p_bsdf);
  // beta_v f_v tr f_x beta_x / d^2 (bidir_connect.h; the camera's f_v is pdf_direction).
  const float d2 = (v.p() - light.p).squaredNorm();
  ++c.light_added;
  return v.beta * f_v * tr * f_x * light.beta * float(w / double(d2));
}

bool VolpathTracer::splat_light(const LightEnd& light, core::Rng& rng, VolpathCounters& c, Vec2& raster,
                                Rgb& value) const {
  if (!light.ok) return false;
  const auto px = m_scene.camera().raster_of(light.p);
  if (!px) {
    ++c.light_blocked;
    return false;
  }
  value = connect_light(light, camera_vertex(), rng, c);
  raster = *px;
  return is_finite(value) && !is_black(value);
}

}  // namespace dp::integrators
