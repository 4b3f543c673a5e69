#include "gradients/bidir_shift.h"

#include <cmath>

#include "gradients/bidir_chain.h"
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
  v.shape = hit.shape;
  v.prim = hit.prim;
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
  out.join = -1;
  out.specular_chain = false;
  out.walked = false;
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

  // Reconnection y_b -> x_{b+1}, or the walk of a specular chain x_{b+1} .. x_{c-1} that
  // rejoins the base at x_c (bidir_chain.h).
  const int b = out.b;
  const BidirVertex& xb = base[size_t(b)];
  const BidirVertex& xn = base[size_t(b + 1)];
  if (!smooth_surface(out.path.back())) return finish(ShiftStatus::not_invertible);
  int join = b + 1;
  const bool chain = xn.kind == BidirKind::surface && !smooth_surface(xn) && !xn.emitter;
  if (chain) {
    while (join < n && chain_interior(base[size_t(join)])) ++join;
    if (!options.walk_chains || join == b + 1 || join >= n || !chain_end(base[size_t(join)])) {
      out.specular_chain = true;
      return finish(ShiftStatus::not_invertible);
    }
    thread_local std::vector<const BidirVertex*> xs;
    xs.clear();
    for (int k = b; k <= join; ++k) xs.push_back(&base[size_t(k)]);
    out.walked = true;
    const ShiftStatus st =
        walk_bidir_chain(scene, xs, out.path.back(), scene::TransportMode::radiance, options.walk, out.chain);
    if (st != ShiftStatus::ok) return finish(st);
  } else if (blocked(scene, out.path.back(), xn)) {
    return finish(ShiftStatus::occluded);
  }
  BidirVertex& yb = out.path.back();
  double J = 1.0;
  if (chain) J = reported_manifold_jacobian(out.chain.end_jacobian, options.fault);
  else if (!xn.infinite())
    J = reported_jacobian(reconnection_jacobian(d3(xb.sp.p), d3(yb.sp.p), d3(xn.sp.p), d3(xn.sp.ng)), options.fault,
                          false);
  const Vec3 wo = chain ? Vec3((out.chain.steps[0].hit.p - yb.sp.p).normalized()) : direction(yb, xn);
  const Rgb f = scatter(yb, yb.wi, wo, scene::TransportMode::radiance);
  if (is_black(f) || !(J > 0.0)) return finish(ShiftStatus::zero_contribution);
  yb.pdf_out = pathspace::bsdf_pdf(yb, yb.wi, wo, scene::TransportMode::radiance);
  yb.weight_out = yb.pdf_out > 0.0f ? Rgb(f / (yb.pdf_out * xb.rr_out)) : Rgb::Zero();
  // Chains: the walk-coordinate density ratio at b, the MIS factor of every vertex up to x_c.
  const double rho_b =
      chain ? double(yb.pdf_out) * J /
                  double(pathspace::bsdf_pdf(xb, xb.wi, direction(xb, xn), scene::TransportMode::radiance))
            : 1.0;
  out.jacobian = J;
  beta *= f * float(J / (double(xb.pdf_out) * double(xb.rr_out)));
  // The walked chain's vertices: the base's Dirac lobes (bidir_chain.h), RR as the base.
  for (int k = b + 1; k < join; ++k) {
    const ChainStep& st = out.chain.steps[size_t(k - b - 1)];
    const BidirVertex& x = base[size_t(k)];
    BidirVertex v = surface_vertex(st.hit, x, (out.path.back().sp.p - st.hit.p).normalized());
    v.beta = beta;
    v.pdf_out = st.pdf;
    v.weight_out = st.weight / x.rr_out;
    out.path.push_back(v);
    beta *= st.weight * (st.pdf / (x.pdf_out * x.rr_out));
  }
  const BidirVertex& xj = base[size_t(join)];
  BidirVertex v = xj;
  v.beta = beta;
  const Vec3 y_prev = out.path.back().sp.p;
  out.path.push_back(v);
  // x_join seen from its new predecessor: its own factor changes (smooth lobe only); the
  // rest is shared.
  if (join + 1 < n && !xj.delta) {
    const Vec3 wi_new = xj.infinite() ? Vec3(-xj.sp.ng) : Vec3((y_prev - xj.sp.p).normalized());
    const Vec3 wo_next = direction(xj, base[size_t(join + 1)]);
    beta *= scatter(xj, wi_new, wo_next, scene::TransportMode::radiance) / (xj.pdf_out * xj.rr_out);
    for (int k = join + 1; k < n; ++k) {
      BidirVertex c = base[size_t(k)];
      c.beta = beta;
      out.path.push_back(c);
      beta *= c.weight_out;
    }
  }
  out.rejoined = true;
  out.join = join;
  finish(ShiftStatus::ok);
  // MIS ratio of strategy t, q_t(T x) |T'| / q_t(x): 1 for the primary ray and Dirac
  // copies (camera-walk coordinates); after a reconnection the forward densities of
  // x_{b+1} and the shared vertices (area measure); after a walked chain rho_b (walk
  // coordinates: the direction at b), 1 through the chain up to x_c, then the shared
  // vertices' forward densities.
  double r = 1.0;
  for (int t = 1; t <= out.alive && t <= n; ++t) {
    const int k = t - 1;
    if (chain && k == b + 1) r *= rho_b;
    else if (chain ? k > join : k > b) r *= remap(out.path[size_t(k)].pdf_fwd) / remap(base[size_t(k)].pdf_fwd);
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
  // Rejoined inside the camera prefix, at x_join (x_{b+1}, or the end c of a walked chain;
  // a connection inside the chain is at a Dirac vertex: no strategy): x_join must have a
  // smooth lobe unless it is the connection vertex.
  const int join = shift.join;
  if (!shift.rejoined || t - 1 < join || (t - 1 > join && base[size_t(join)].delta)) return o;
  o.exists = true;
  o.test_visibility = false;
  o.same_reverse = t - 1 >= join + 1;
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
  out.walked = false;
  if (s < 2) return fail(ShiftStatus::not_invertible);  // a light seen directly is never shifted
  const BidirVertex& x1 = light[s - 1];
  const scene::PerspectiveCamera& cam = scene.camera();
  const Ray ray = cam.generate_ray(raster + offset);
  scene::SurfaceHit hit;
  if (!scene.intersect(ray, hit)) return fail(ShiftStatus::miss);
  BidirVertex y1 = surface_vertex(hit, x1, Vec3::Zero());
  y1.delta = false;  // the offset light subpath ends at y_1
  if (!smooth_surface(y1)) return fail(ShiftStatus::not_invertible);
  // z = light[e]: the vertex y_1 rejoins (e = s - 2), or the end of a specular chain.
  int e = s - 2;
  const bool chain = light[e].kind != BidirKind::light && light[e].delta;
  if (chain) {
    while (e >= 1 && chain_interior(light[e])) --e;
    if (!options.walk_chains || e == s - 2 || !chain_end(light[e]) || light[e].delta) {
      out.specular_chain = true;
      return fail(ShiftStatus::not_invertible);
    }
    thread_local std::vector<const BidirVertex*> xs;  // camera order: x_1 .. x_c = light[e]
    xs.clear();
    for (int j = s - 1; j >= e; --j) xs.push_back(&light[j]);
    out.walked = true;
    const ShiftStatus st = walk_bidir_chain(scene, xs, y1, scene::TransportMode::importance, options.walk, out.chain);
    if (st != ShiftStatus::ok) return fail(st);
  } else if (blocked(scene, y1, light[e])) {
    return fail(ShiftStatus::occluded);
  }
  const BidirVertex& z = light[e];
  out.light.assign(light, light + (e + 1));
  Rgb dirac = Rgb::Ones();  // the walked chain's Dirac factors over the base's densities
  if (chain)
    for (int j = e + 1; j <= s - 2; ++j) {  // light order: from z toward y_1
      const ChainStep& st = out.chain.steps[size_t(s - 2 - j)];
      const BidirVertex& x = light[j];
      BidirVertex v = surface_vertex(st.hit, x, Vec3::Zero());
      v.beta = Rgb::Zero();
      v.pdf_out = st.pdf;
      v.weight_out = st.weight / x.rr_out;
      pathspace::append_vertex(scene, out.light, v, scene::TransportMode::importance);
      dirac *= st.weight * (st.pdf / (x.pdf_out * x.rr_out));
    }
  y1.beta = Rgb::Zero();
  pathspace::append_vertex(scene, out.light, y1, scene::TransportMode::importance);
  const BidirVertex& y = out.light.back();  // wi re-derived: toward its light-side neighbour
  // f(T x)|T'| / p(x) in area measure: the light prefix up to z over its sampling density,
  // z's factor toward its new successor with the area conversion at y_1 through the chain
  // (d w_z / dA(y_1); without a chain |cos_y1| / d^2), the chain's Dirac factors, y_1's
  // factor toward the camera, the camera's factor, and |dy_1/dx_1| = p_cam(x_1) / p_cam(y_1).
  const BidirVertex& z_next = out.light[size_t(e + 1)];
  const Vec3 w_z = z.infinite() ? Vec3(-z.sp.ng) : Vec3((z_next.sp.p - z.sp.p).normalized());
  const Vec3 w_z_base = z.infinite() ? Vec3(-z.sp.ng) : Vec3((light[e + 1].sp.p - z.sp.p).normalized());
  auto emit = [&](const Vec3& w) {
    return z.kind == BidirKind::light ? pathspace::light_emit_cos(z, w)
                                      : scatter(z, z.wi, w, scene::TransportMode::importance);
  };
  const Rgb fz = emit(w_z);
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
  // [d w_z / dA(y_1)] / [d w_z / dA(x_1)]
  const double area_ratio =
      chain ? reported_manifold_jacobian(out.chain.start_density, options.fault) : conv(y) / conv(x1);
  if (!(px > 0.0) || !(py > 0.0) || !(area_ratio > 0.0) || !std::isfinite(area_ratio))
    return fail(ShiftStatus::zero_contribution);
  out.jacobian = reported_jacobian(px / py, options.fault, false);
  // camera factor of y_1 (pdf_direction / d^2, times fy's cosine) = p_cam(y_1) / |cos_y1|.
  const double cos_y = std::abs(double(y.sp.ng.dot(to_cam)));
  if (!(cos_y > 0.0)) return fail(ShiftStatus::zero_contribution);
  const double scale = (py / cos_y) * out.jacobian * area_ratio / (double(z.pdf_out) * double(z.rr_out));
  out.value = z.beta * fz * dirac * fy * float(scale);
  if (chain) {  // q in light-walk coordinates: the direction at z, d w'_z / d w_z = area_ratio J_A
    auto pdf_dir = [&](const Vec3& w) {
      return double(z.kind == BidirKind::light ? pathspace::light_pdf_dir(z, w)
                                               : pathspace::bsdf_pdf(z, z.wi, w, scene::TransportMode::importance));
    };
    out.mis_ratio = pdf_dir(w_z) / pdf_dir(w_z_base) * area_ratio * (px / py);
  } else {
    out.mis_ratio = remap(y.pdf_fwd) / remap(x1.pdf_fwd) * (px / py);
  }
  if (!std::isfinite(out.mis_ratio)) return fail(ShiftStatus::zero_contribution);
  out.status = ShiftStatus::ok;
  return true;
}

}  // namespace dp::gradients
