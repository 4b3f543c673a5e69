#include "gradients/volume_photon_reconnect.h"

#include "pathspace/bidir_light.h"
#include "scene/bsdf/bsdf.h"
#include "scene/emitters/emitter.h"
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"
#include "scene/scene.h"

namespace dp::gradients {

float photon_volume_pdf(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                        ReconnectFault fault) {
  const Vec3 d = b - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return 0.0f;
  const float t = std::sqrt(t2);
  const float phase = scene::HenyeyGreenstein(medium.phase).pdf(parent.w_in, d / t);
  // dV = t^2 dw dt (Eq. 4's G at two medium vertices).
  return phase * scene::free_flight_pdf(medium, t) / (fault == ReconnectFault::no_volume_factor ? 1.0f : t2);
}

Rgb photon_edge_throughput(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                           ReconnectFault fault) {
  const Vec3 d = b - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return Rgb::Zero();
  const float t = std::sqrt(t2);
  const float phase = scene::HenyeyGreenstein(medium.phase).eval(parent.w_in, d / t);
  // rho_p(a) tau(a, b) G(a, b) sigma_s(b) (Eqs. 2-4).
  return phase * scene::transmittance(medium, t) * medium.sigma_s / (fault == ReconnectFault::no_volume_factor ? 1.0f : t2);
}

const char* to_string(ParentKind kind) {
  switch (kind) {
    case ParentKind::none: return "none";
    case ParentKind::medium: return "medium";
    case ParentKind::surface: return "surface";
    case ParentKind::light: return "light";
    case ParentKind::specular: return "specular";
    case ParentKind::light_infinite: return "light_infinite";
  }
  return "unknown";
}

bool parent_direction(const PhotonParent& parent, const Vec3& w, Rgb& rho, float& p_dir) {
  rho = Rgb::Zero();
  p_dir = 0.0f;
  if (parent.kind == ParentKind::surface) {
    const Vec3 wi = parent.shading.to_local(parent.w), wo = parent.shading.to_local(w);
    // The photon tracer's sidedness rule (geometric and shading normals agree on wo's side).
    if (!(parent.ng.dot(w) * wo.z() > 0.0f)) return false;
    const scene::BsdfContext ctx{parent.uv, scene::TransportMode::importance};
    rho = parent.bsdf->eval_pdf(ctx, wi, wo, p_dir) * std::abs(wo.z());
  } else if (parent.kind == ParentKind::light) {
    pathspace::BidirVertex y0;
    y0.kind = pathspace::BidirKind::light;
    y0.emitter = parent.emitter;
    y0.sp.p = parent.a;
    y0.sp.ng = parent.ng;
    y0.sp.shading = Frame::from_normal(parent.ng);
    y0.sp.uv = parent.uv;
    rho = pathspace::light_emit_cos(y0, w);  // Le cos (area), intensity (point, spot)
    p_dir = pathspace::light_pdf_dir(y0, w);
  } else {
    return false;
  }
  return p_dir > 0.0f && !is_black(rho);
}

bool photon_edge(const PhotonParent& parent, const scene::HomogeneousMedium& medium, const Vec3& x, Rgb& f, float& pdf,
                 ReconnectFault fault) {
  f = Rgb::Zero();
  pdf = 0.0f;
  if (parent.kind == ParentKind::medium) {
    const MediumParent m{parent.a, parent.w};
    f = photon_edge_throughput(m, medium, x, fault);
    pdf = photon_volume_pdf(m, medium, x, fault);
    return pdf > 0.0f && !is_black(f);
  }
  const Vec3 d = x - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return false;
  const float t = std::sqrt(t2);
  Rgb rho;
  float p_dir = 0.0f;
  if (!parent_direction(parent, d / t, rho, p_dir)) return false;
  const float g = fault == ReconnectFault::no_volume_factor ? 1.0f : 1.0f / t2;  // Eq. 4, no cosine at b
  f = rho * scene::transmittance(medium, t) * medium.sigma_s * g;
  pdf = p_dir * scene::free_flight_pdf(medium, t) * g;
  return pdf > 0.0f && !is_black(f);
}

bool anchor_direction(const scene::Scene& scene, const PhotonParent& parent, const Vec3& w, Rgb& rho, float& p_dir) {
  if (parent.kind != ParentKind::medium) return parent_direction(parent, w, rho, p_dir);
  const scene::HenyeyGreenstein hg(scene.media()[size_t(parent.medium)].phase);
  rho = Rgb::Constant(hg.eval(parent.w, w));
  p_dir = hg.pdf(parent.w, w);
  return p_dir > 0.0f;
}

SegmentMedia walk_segment(const scene::Scene& scene, const Vec3& o, const Vec3& w, float t, int medium) {
  SegmentMedia s;
  s.medium = medium;
  float start = 0.0f;  // distance from o of the current sub-segment's start
  Ray ray;
  ray.o = o;
  ray.d = w;
  ray.tmin = scene::Scene::epsilon_at(o);
  ray.tmax = t;
  scene::SurfaceHit hit;
  const int cam_medium = scene.camera_medium();
  for (int crossings = 0;; ++crossings) {
    if (!scene.intersect(ray, hit)) break;
    if (!scene::is_index_matched(hit) || crossings >= 16) {
      s.blocked = true;
      return s;
    }
    const float at = start + hit.t;  // distance of the boundary from o
    if (s.medium >= 0) {
      const scene::HomogeneousMedium& m = scene.media()[size_t(s.medium)];
      s.tr *= scene::transmittance(m, at - start);
      s.p_pass *= double(scene::free_flight_pass_probability(m, at - start));
    }
    s.medium = scene::medium_toward(hit, w, s.medium, cam_medium);
    start = at;
    ray.o = hit.p;
    ray.tmin = scene::Scene::epsilon_at(hit.p);
    ray.tmax = t - at;
    if (!(ray.tmax > ray.tmin)) break;
  }
  s.last = t - start;
  return s;
}

namespace {

// f(a -> x) and p(x | a) through index-matched boundaries (reconnect_photon_edge).
bool walked_edge(const scene::Scene& scene, const PhotonParent& parent, int photon_medium, const Vec3& x, Rgb& f,
                 float& pdf, bool& blocked, ReconnectFault fault) {
  f = Rgb::Zero();
  pdf = 0.0f;
  const Vec3 d = x - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return false;
  const float t = std::sqrt(t2);
  const Vec3 w = d / t;
  Rgb rho;
  float p_dir = 0.0f;
  if (!anchor_direction(scene, parent, w, rho, p_dir)) return false;
  const SegmentMedia seg = walk_segment(scene, parent.a, w, t, parent.medium);
  if (seg.blocked || seg.medium != photon_medium || seg.medium < 0) {
    blocked = true;
    return false;
  }
  const scene::HomogeneousMedium& m = scene.media()[size_t(seg.medium)];
  const float g = fault == ReconnectFault::no_volume_factor ? 1.0f : 1.0f / t2;  // Eq. 4, no cosine at x
  f = rho * seg.tr * scene::transmittance(m, seg.last) * m.sigma_s * g;
  pdf = float(double(p_dir) * seg.p_pass * double(scene::free_flight_pdf(m, seg.last)) * double(g));
  return pdf > 0.0f && !is_black(f);
}

}  // namespace

PhotonReconnection reconnect_photon_edge(const scene::Scene& scene, const PhotonParent& parent, int photon_medium,
                                         const Vec3& b, const Vec3& b_offset, bool& blocked, ReconnectFault fault) {
  PhotonReconnection r;
  blocked = false;
  Rgb fb, fo;
  float pb = 0.0f, po = 0.0f;
  // A surface parent's medium is that of the side the base photon left into: an offset
  // on the other side (reflection <-> transmission) would start in an unknown medium.
  if (parent.kind == ParentKind::surface &&
      (parent.ng.dot(b - parent.a) > 0.0f) != (parent.ng.dot(b_offset - parent.a) > 0.0f)) {
    blocked = true;
    return r;
  }
  bool base_blocked = false;
  if (!walked_edge(scene, parent, photon_medium, b, fb, pb, base_blocked, fault)) return r;  // numerically lost: zero
  if (!walked_edge(scene, parent, photon_medium, b_offset, fo, po, blocked, fault)) return r;
  for (int c = 0; c < 3; ++c) r.ratio[c] = fb[c] > 0.0f ? fo[c] / fb[c] : 0.0f;
  r.pdf_ratio = double(po) / double(pb);
  r.w = (b_offset - parent.a).normalized();
  r.ok = !is_black(r.ratio) && r.pdf_ratio > 0.0 && std::isfinite(r.pdf_ratio) && is_finite(r.ratio);
  return r;
}

PhotonReconnection reconnect_photon(const PhotonParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                                    const Vec3& b_offset, ReconnectFault fault) {
  PhotonReconnection r;
  Rgb fb, fo;
  float pb = 0.0f, po = 0.0f;
  if (!photon_edge(parent, medium, b, fb, pb, fault) || !photon_edge(parent, medium, b_offset, fo, po, fault)) return r;
  for (int c = 0; c < 3; ++c) r.ratio[c] = fb[c] > 0.0f ? fo[c] / fb[c] : 0.0f;
  r.pdf_ratio = double(po) / double(pb);
  r.w = (b_offset - parent.a).normalized();
  r.ok = !is_black(r.ratio) && r.pdf_ratio > 0.0 && std::isfinite(r.pdf_ratio) && is_finite(r.ratio);
  return r;
}

}  // namespace dp::gradients
