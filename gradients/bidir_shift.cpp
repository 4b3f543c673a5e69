#include "gradients/bidir_shift.h"

#include <cmath>

#include "gradients/jacobians.h"
#include "gradients/shift_helpers.h"
#include "pathspace/bidir_light.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/scatter.h"

namespace dp::gradients {

using pathspace::BidirKind;
using pathspace::BidirVertex;

namespace {

double remap(float pdf) { return pdf != 0.0f ? double(pdf) : 1.0; }

// Connectable as a reconnection end: a light endpoint, or a surface with a smooth lobe.
bool smooth_surface(const BidirVertex& v) { return v.bsdf && !v.bsdf->is_purely_delta(); }

// f(wi, wo) |cos wo| at surface vertex v in `mode` (shading normal), 0 on a sidedness
// violation of either direction (as pathspace::connect).
Rgb scatter(const BidirVertex& v, const Vec3& wi_world, const Vec3& wo_world, scene::TransportMode mode) {
  if (!v.bsdf) return Rgb::Zero();
  const Vec3 wi = v.sp.shading.to_local(wi_world), wo = v.sp.shading.to_local(wo_world);
  if (!(v.sp.ng.dot(wi_world) * wi.z() > 0.0f) || !(v.sp.ng.dot(wo_world) * wo.z() > 0.0f)) return Rgb::Zero();
  return v.bsdf->eval(scene::BsdfContext{v.sp.uv, mode}, wi, wo) * std::abs(wo.z());
}

bool blocked(const scene::Scene& scene, const BidirVertex& from, const BidirVertex& to) {
  if (to.infinite()) return scene.occluded(scene.spawn_ray(from.sp, to.sp.ng));
  return scene.occluded(scene.spawn_segment(from.sp, to.sp.p));
}

BidirVertex surface_vertex(const scene::SurfaceHit& hit, const BidirVertex& like, const Vec3& toward_prev) {
  BidirVertex v;
  v.sp = hit;
  v.bsdf = hit.bsdf;
  v.emitter = hit.emitter;
  v.kind = BidirKind::surface;
  v.wi = toward_prev;
  v.delta = like.delta;
  v.lobe = like.lobe;
  v.u_lobe = like.u_lobe;
  v.rr_out = like.rr_out;
  return v;
}

// Unit direction from `from` toward vertex `to` (the light's direction at infinity).
Vec3 direction(const BidirVertex& from, const BidirVertex& to) {
  return to.infinite() ? Vec3(to.sp.ng) : Vec3((to.sp.p - from.sp.p).normalized());
}

}  // namespace

double camera_area_pdf(const scene::Scene& scene, const BidirVertex& v) {
  const Vec3 d = v.sp.p - scene.camera().position();
  const double d2 = double(d.squaredNorm());
  if (!(d2 > 0.0)) return 0.0;
  const Vec3 w = d / std::sqrt(float(d2));
  return double(scene.camera().pdf_direction(w)) * std::abs(double(v.sp.ng.dot(w))) / d2;
}

void shift_camera_subpath(const scene::Scene& scene, const std::vector<BidirVertex>& base, const Vec2& raster,
                          const Vec2& offset, const BidirShiftOptions& options, CameraSubpathShift& out) {
  out.path.clear();
  out.status = ShiftStatus::ok;
  out.alive = 0;
  out.b = -1;
  out.rejoined = false;
  out.specular_chain = false;
  out.jacobian = 1.0;
  out.mis_ratio.assign(base.size() + 1, 1.0);
  const int n = int(base.size());
  if (n == 0) return;
  auto finish = [&](ShiftStatus s) {
    out.status = s;
    out.alive = int(out.path.size());
    pathspace::recompute_densities(scene, out.path, scene::TransportMode::radiance);
  };
  const scene::PerspectiveCamera& cam = scene.camera();
  out.path.push_back(base[0]);
  Ray ray = cam.generate_ray(raster + offset);
  out.path[0].pdf_out = cam.pdf_direction(ray.d);
  Rgb beta = Rgb::Ones();  // We / p = 1 in both pixels (raster coordinates)
  scene::SurfaceHit hit;
  bool from_surface = false;  // rays between vertices are anchored as the walk's
  // Primary ray and Dirac copies up to the first smooth-lobe vertex b.
  for (int k = 1; k < n; ++k) {
    const BidirVertex& x = base[size_t(k)];
    const BidirVertex& prev = out.path.back();
    const bool found = from_surface ? pathspace::next_hit(scene, hit, ray.d, hit) : scene.intersect(ray, hit);
    if (x.kind == BidirKind::light) {  // the base escaped to the environment
      if (found) return finish(ShiftStatus::miss);
      BidirVertex v = x;
      v.sp.ng = ray.d;
      v.sp.p = prev.sp.p + ray.d * (4.0f * pathspace::infinite_disk_radius(scene));
      v.beta = beta;
      out.path.push_back(v);
      out.b = k;
      return finish(ShiftStatus::ok);
    }
    if (!found) return finish(ShiftStatus::miss);
    const Vec3 d = prev.sp.p - hit.p;
    const float len = d.norm();
    if (!(len > 0.0f)) return finish(ShiftStatus::zero_contribution);
    BidirVertex v = surface_vertex(hit, x, d / len);
    v.beta = beta;
    out.path.push_back(v);
    if (!x.delta) {
      out.b = k;
      break;
    }
    // Same Dirac lobe at y_k (Jacobian 1); RR follows the base.
    BidirVertex& y = out.path.back();
    if (!y.bsdf) return finish(ShiftStatus::zero_contribution);
    const Vec3 wi = hit.shading.to_local(y.wi);
    if (!(hit.ng.dot(y.wi) * wi.z() > 0.0f)) return finish(ShiftStatus::zero_contribution);
    const auto bs = pathspace::sample_dirac_lobe(*y.bsdf, scene::BsdfContext{hit.uv, scene::TransportMode::radiance},
                                                 wi, x.lobe, x.u_lobe);
    if (!bs || is_black(bs->weight)) return finish(ShiftStatus::zero_contribution);
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!(hit.ng.dot(wo) * bs->wo.z() > 0.0f)) return finish(ShiftStatus::zero_contribution);
    y.pdf_out = bs->pdf;
    y.weight_out = bs->weight / x.rr_out;
    beta *= bs->weight * (bs->pdf / (x.pdf_out * x.rr_out));
    ray.d = wo;
    from_surface = true;
  }
  if (out.b < 0 || out.b + 1 >= n) return finish(ShiftStatus::ok);

  // Reconnection y_b -> x_{b+1}.
  const int b = out.b;
  const BidirVertex& xb = base[size_t(b)];
  const BidirVertex& xn = base[size_t(b + 1)];
  BidirVertex& yb = out.path.back();
  if (!smooth_surface(yb)) return finish(ShiftStatus::not_invertible);
  if (xn.kind == BidirKind::surface && !smooth_surface(xn) && !xn.emitter) {
    out.specular_chain = true;
    return finish(ShiftStatus::not_invertible);
  }
  if (blocked(scene, yb, xn)) return finish(ShiftStatus::occluded);
  double J = 1.0;
  if (!xn.infinite())
    J = reconnection_jacobian(d3(xb.sp.p), d3(yb.sp.p), d3(xn.sp.p), d3(xn.sp.ng));
  J = reported_jacobian(J, options.fault, false);
  const Vec3 wo = direction(yb, xn);
  const Rgb f = scatter(yb, yb.wi, wo, scene::TransportMode::radiance);
  if (is_black(f) || !(J > 0.0)) return finish(ShiftStatus::zero_contribution);
  yb.pdf_out = pathspace::bsdf_pdf(yb, yb.wi, wo, scene::TransportMode::radiance);
  yb.weight_out = yb.pdf_out > 0.0f ? Rgb(f / (yb.pdf_out * xb.rr_out)) : Rgb::Zero();
  out.jacobian = J;
  beta *= f * float(J / (double(xb.pdf_out) * double(xb.rr_out)));
  BidirVertex v = xn;
  v.beta = beta;
  out.path.push_back(v);
  // x_{b+1} seen from y_b: its own factor changes (smooth lobe only); the rest is shared.
  if (b + 2 < n && !xn.delta) {
    const Vec3 wi_new = xn.infinite() ? Vec3(-xn.sp.ng) : Vec3((yb.sp.p - xn.sp.p).normalized());
    const Vec3 wo_next = direction(xn, base[size_t(b + 2)]);
    beta *= scatter(xn, wi_new, wo_next, scene::TransportMode::radiance) / (xn.pdf_out * xn.rr_out);
    for (int k = b + 2; k < n; ++k) {
      BidirVertex c = base[size_t(k)];
      c.beta = beta;
      out.path.push_back(c);
      beta *= c.weight_out;
    }
  }
  out.rejoined = true;
  finish(ShiftStatus::ok);
  // MIS ratio of strategy t: the shared vertices' forward densities over the base's (the
  // moved vertices' camera-walk factors are 1: primary ray and Dirac copies).
  double r = 1.0;
  for (int t = 1; t <= out.alive && t <= n; ++t) {
    const int k = t - 1;
    if (k > b) r *= remap(out.path[size_t(k)].pdf_fwd) / remap(base[size_t(k)].pdf_fwd);
    out.mis_ratio[size_t(t)] = r;
  }
}

StrategyOffset camera_strategy_offset(const CameraSubpathShift& shift, const std::vector<BidirVertex>& base, int t) {
  StrategyOffset o;
  if (t - 1 >= shift.alive) return o;
  const int bst = shift.b >= 0 ? std::min(shift.b, t - 1) : t - 1;
  if (bst == t - 1) {  // the offset prefix reconnects at the connection itself
    o.exists = true;
    return o;
  }
  // Reconnected inside the camera prefix: x_{b+1} must have a smooth lobe unless it is the
  // connection vertex.
  if (!shift.rejoined || (t - 1 > bst + 1 && base[size_t(bst + 1)].delta)) return o;
  o.exists = true;
  o.test_visibility = false;
  o.same_reverse = t - 1 >= bst + 2;
  o.mis_ratio = shift.mis_ratio[size_t(t)];
  return o;
}

bool shift_light_tracing(const scene::Scene& scene, const BidirVertex* light, int s, const Vec2& raster,
                         const Vec2& offset, const BidirShiftOptions& options, LightTracingShift& out) {
  out.light.clear();
  out.value = Rgb::Zero();
  out.mis_ratio = 1.0;
  out.jacobian = 1.0;
  out.specular_chain = false;
  auto fail = [&](ShiftStatus st) {
    out.status = st;
    return false;
  };
  if (s < 2) return fail(ShiftStatus::not_invertible);  // a light seen directly is never shifted
  const BidirVertex& x1 = light[s - 1];
  const BidirVertex& z = light[s - 2];
  const scene::PerspectiveCamera& cam = scene.camera();
  const Ray ray = cam.generate_ray(raster + offset);
  scene::SurfaceHit hit;
  if (!scene.intersect(ray, hit)) return fail(ShiftStatus::miss);
  BidirVertex y1 = surface_vertex(hit, x1, Vec3::Zero());
  y1.delta = false;  // the offset light subpath ends at y_1
  if (!smooth_surface(y1)) return fail(ShiftStatus::not_invertible);
  if (z.kind != BidirKind::light && z.delta) {  // a specular chain after b = y_1
    out.specular_chain = true;
    return fail(ShiftStatus::not_invertible);
  }
  if (blocked(scene, y1, z)) return fail(ShiftStatus::occluded);
  out.light.assign(light, light + (s - 1));
  y1.beta = Rgb::Zero();
  pathspace::append_vertex(scene, out.light, y1, scene::TransportMode::importance);
  const BidirVertex& y = out.light.back();  // wi re-derived: toward z
  // f(T x)|T'| / p(x) in area measure: the light prefix up to z over its sampling density,
  // z's factor toward y_1 with the area conversion at y_1, y_1's factor toward the camera,
  // the camera's factor, and |dy_1/dx_1| = p_cam(x_1) / p_cam(y_1).
  const Vec3 w_zy = -y.wi;
  const Rgb fz = z.kind == BidirKind::light ? pathspace::light_emit_cos(z, w_zy)
                                            : scatter(z, z.wi, w_zy, scene::TransportMode::importance);
  const Vec3 to_cam = (cam.position() - y.sp.p).normalized();
  const Rgb fy = scatter(y, y.wi, to_cam, scene::TransportMode::importance);
  if (is_black(fz) || is_black(fy)) return fail(ShiftStatus::zero_contribution);
  auto conv = [&](const BidirVertex& v) {  // area factor at v of a direction leaving z
    if (z.infinite()) return std::abs(double(v.sp.ng.dot(z.sp.ng)));
    const Vec3 d = z.sp.p - v.sp.p;
    const double d2 = double(d.squaredNorm());
    return std::abs(double(v.sp.ng.dot(d))) / (std::sqrt(d2) * d2);
  };
  const double px = camera_area_pdf(scene, x1), py = camera_area_pdf(scene, y);
  const double cx = conv(x1);
  if (!(px > 0.0) || !(py > 0.0) || !(cx > 0.0)) return fail(ShiftStatus::zero_contribution);
  out.jacobian = reported_jacobian(px / py, options.fault, false);
  // camera factor of y_1 (pdf_direction / d^2, times fy's cosine) = p_cam(y_1) / |cos_y1|.
  const double cos_y = std::abs(double(y.sp.ng.dot(to_cam)));
  if (!(cos_y > 0.0)) return fail(ShiftStatus::zero_contribution);
  const double scale = (py / cos_y) * out.jacobian * conv(y) / (cx * double(z.pdf_out) * double(z.rr_out));
  out.value = z.beta * fz * fy * float(scale);
  out.mis_ratio = remap(y.pdf_fwd) / remap(x1.pdf_fwd) * (px / py);
  out.status = ShiftStatus::ok;
  return true;
}

}  // namespace dp::gradients
