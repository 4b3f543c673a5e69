#include "gradients/bidir_shift.h"

#include <cmath>

#include "gradients/bidir_chain.h"
#include "gradients/bidir_helpers.h"
#include "gradients/jacobians.h"
#include "gradients/shift_helpers.h"
#include "pathspace/bidir_light.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/scatter.h"

namespace dp::gradients {

using pathspace::BidirKind;
using pathspace::BidirVertex;

using namespace bidir;

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
  out.value = Rgb::Zero();
  out.mis_ratio = 1.0;
  out.jacobian = 1.0;
  out.light.clear();
  out.specular_chain = out.walked = false;
  auto fail = [&](ShiftStatus st) {
    out.status = st;
    return false;
  };
  if (s < 2) return fail(ShiftStatus::not_invertible);  // a light seen directly is never shifted
  const BidirVertex& x1 = light[s - 1];
  const scene::PerspectiveCamera& cam = scene.camera();
  const Ray ray = cam.generate_ray(raster + offset);
  scene::SurfaceHit hit;
  if (!scene.intersect(ray, hit)) return fail(ShiftStatus::miss);
  const BidirVertex y1 = surface_vertex(hit, x1, Vec3::Zero());
  if (!smooth_surface(y1)) return fail(ShiftStatus::not_invertible);
  // The light subpath rejoined at y_1 (light_rejoin.h: reconnection or chain walk).
  if (!rejoin_light_subpath(scene, light, s - 1, y1, options, out)) return false;
  const BidirVertex& y = out.light.back();
  // f(T x)|T'| / p(x) in area measure: the light side's throughput at y_1 over the base's
  // density at x_1 (light_rejoin.h), y_1's factor toward the camera, the camera's factor,
  // and |dy_1/dx_1| = p_cam(x_1) / p_cam(y_1).
  const Vec3 to_cam = (cam.position() - y.sp.p).normalized();
  const Rgb fy = scatter(y, y.wi, to_cam, scene::TransportMode::importance);
  if (is_black(fy)) return fail(ShiftStatus::zero_contribution);
  const double px = camera_area_pdf(scene, x1), py = camera_area_pdf(scene, y);
  if (!(px > 0.0) || !(py > 0.0)) return fail(ShiftStatus::zero_contribution);
  out.jacobian = reported_jacobian(px / py, options.fault, false);
  // camera factor of y_1 (pdf_direction / d^2, times fy's cosine) = p_cam(y_1) / |cos_y1|.
  const double cos_y = std::abs(double(y.sp.ng.dot(to_cam)));
  if (!(cos_y > 0.0)) return fail(ShiftStatus::zero_contribution);
  out.value = out.throughput * fy * float((py / cos_y) * out.jacobian);
  // q in light-walk coordinates: the direction at z, d w'_z / d w_z = area_ratio J_A (for
  // a reconnection the same as y_1's forward density ratio, kept in that form).
  if (out.walked) out.mis_ratio = out.direction_ratio * out.area_ratio * (px / py);
  else out.mis_ratio = remap(y.pdf_fwd) / remap(x1.pdf_fwd) * (px / py);
  if (!std::isfinite(out.mis_ratio)) return fail(ShiftStatus::zero_contribution);
  out.status = ShiftStatus::ok;
  return true;
}

}  // namespace dp::gradients
