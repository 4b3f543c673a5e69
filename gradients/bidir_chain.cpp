#include "gradients/bidir_chain.h"

#include <cmath>

#include "gradients/manifold_shift.h"
#include "gradients/shift_helpers.h"
#include "manifold/constraints.h"
#include "manifold/local_geometry.h"
#include "pathspace/scatter.h"
#include "scene/emitters/emitter.h"
#include "scene/shapes/shape.h"

namespace dp::gradients {

using manifold::Chain;
using manifold::ChainVertex;
using manifold::Interaction;
using manifold::WalkStatus;
using pathspace::BidirKind;
using pathspace::BidirVertex;

namespace {

bool area_light(const BidirVertex& v) {
  return v.kind == BidirKind::light && v.emitter && v.emitter->kind() == scene::EmitterKind::area;
}

// The pinned end x_c: a surface vertex refined in double on its shape, or an area light's
// endpoint from its float data (a pinned vertex never moves: only its position and
// normal enter), tagged with its shape so that re-traces may end on it.
std::optional<ChainVertex> pinned(const scene::Scene& scene, const BidirVertex& c) {
  if (c.kind == BidirKind::surface) return manifold::make_vertex(scene, pathspace::surface_hit(c), Interaction::reflection);
  if (!area_light(c)) return std::nullopt;
  const scene::Shape* shape = static_cast<const scene::AreaEmitter*>(c.emitter)->shape();
  scene::SurfacePoint sp = c.sp;
  sp.dpdu = sp.shading.s;  // any tangent: a light sample carries none
  ChainVertex v = manifold::make_vertex(sp, Interaction::reflection);
  for (size_t i = 0; i < scene.shapes().size(); ++i)
    if (scene.shapes()[i].get() == shape) v.shape = int32_t(i);
  if (v.shape < 0) return std::nullopt;
  return v;
}

// A chain vertex x_j between neighbours a and b: reflection or refraction from the sides
// of its neighbours; the refraction's eta (index behind the geometric normal over the one
// in front, manifold/chain.h) from the base's own lobe replayed from its sampling side.
std::optional<ChainVertex> interior(const scene::Scene& scene, const BidirVertex& x, const Vec3& a, const Vec3& b,
                                    scene::TransportMode mode) {
  const bool refraction = x.sp.ng.dot(a - x.sp.p) * x.sp.ng.dot(b - x.sp.p) < 0.0f;
  double eta = 1.0;
  if (refraction) {
    const auto bs = pathspace::sample_dirac_lobe(*x.bsdf, scene::BsdfContext{x.sp.uv, mode},
                                                 x.sp.shading.to_local(x.wi), x.lobe, x.u_lobe);
    if (!bs || bs->eta == 1.0f) return std::nullopt;  // index-matched: no half vector
    eta = x.sp.ng.dot(x.wi) > 0.0f ? double(bs->eta) : 1.0 / double(bs->eta);
  }
  return manifold::make_vertex(scene, pathspace::surface_hit(x), refraction ? Interaction::refraction : Interaction::reflection,
                               eta);
}

// |cos| at the pinned start (geometric normal) toward x_1; 1 without a surface.
double start_cosine(const Chain& c) {
  if (!c.v[0].has_surface) return 1.0;
  return std::abs((c.v[1].p() - c.v[0].p()).normalized().dot(c.v[0].f.ng));
}

// G / |cos_c| of a chain pinned at c: d w_c / dA_b.
WalkStatus start_density(const Chain& c, double& d) {
  double G = 0.0;
  const WalkStatus st = manifold::generalized_geometry(c, G);
  if (st != WalkStatus::ok) return st;
  const double cc = start_cosine(c);
  if (!(cc > 0.0) || !(G > 0.0)) return WalkStatus::grazing;
  d = G / cc;
  return WalkStatus::ok;
}

// The manifold chain pinned at x_c (v[0]) through the interior vertices (given in camera
// order x_{b+1} .. x_{c-1}) to the end `end` (v[n]).
bool build_chain(const scene::Scene& scene, const ChainVertex& c, const std::vector<ChainVertex>& inner_cam_order,
                 const scene::SurfaceHit& end, Chain& ch) {
  ch = Chain{};
  ch.pin = manifold::Pin::position;
  ch.v.push_back(c);
  for (auto it = inner_cam_order.rbegin(); it != inner_cam_order.rend(); ++it) ch.v.push_back(*it);
  const auto e = manifold::make_vertex(scene, end, Interaction::reflection);
  if (!e) return false;
  ch.v.push_back(*e);
  return true;
}

}  // namespace

bool chain_interior(const BidirVertex& v) {
  return v.kind == BidirKind::surface && v.delta && v.bsdf && v.bsdf->is_purely_delta() && !v.emitter &&
         v.shape >= 0;
}

bool chain_end(const BidirVertex& v) {
  if (area_light(v)) return true;
  return v.kind == BidirKind::surface && v.shape >= 0 && (v.emitter || (v.bsdf && !v.bsdf->is_purely_delta()));
}

ShiftStatus walk_bidir_chain(const scene::Scene& scene, std::span<const BidirVertex* const> x, const BidirVertex& yb,
                             scene::TransportMode mode, const manifold::WalkSettings& settings, BidirChainWalk& out) {
  out.steps.clear();
  out.stats = manifold::WalkStats{};
  out.walk_status = WalkStatus::invalid_input;
  const int m = int(x.size()) - 1;  // x[0] = x_b, x[m] = x_c
  if (m < 2 || yb.shape < 0 || x[0]->shape < 0) return ShiftStatus::not_invertible;
  const auto c = pinned(scene, *x[size_t(m)]);
  if (!c) return ShiftStatus::not_invertible;
  thread_local std::vector<ChainVertex> inner;
  inner.clear();
  for (int j = 1; j < m; ++j) {
    const auto v = interior(scene, *x[size_t(j)], x[size_t(j - 1)]->sp.p, x[size_t(j + 1)]->sp.p, mode);
    if (!v) return ShiftStatus::not_invertible;
    inner.push_back(*v);
  }
  Chain base;
  if (!build_chain(scene, *c, inner, pathspace::surface_hit(*x[0]), base)) return ShiftStatus::not_invertible;
  // The chain in exact (double) form, re-traced along the direction the base sampled: at
  // x_b for the camera walk (manifold::walk_exact), at x_c for the light walk (a re-trace
  // from the pinned start); then walked to y_b.
  manifold::WalkSettings exact_settings = settings;
  exact_settings.exact_input = true;  // solve() re-traces first
  const auto solve = [&](const Chain& ch, const Vec3& x_next, const Vec3& target, Chain& exact,
                         manifold::WalkResult& w) {
    if (mode == scene::TransportMode::radiance)
      return manifold::walk_exact(scene, ch, d3(x_next), d3(target), exact_settings, exact, w, out.stats);
    const WalkStatus r = manifold::retrace(scene, ch, ch.v[1].p(), exact);
    ++out.stats.traces;
    if (r != WalkStatus::ok) {
      out.stats.record(r, 0);
      return r;
    }
    w = manifold::walk(scene, exact, d3(target), exact_settings, &out.stats);
    return w.status;
  };
  Chain exact;
  manifold::WalkResult w;
  WalkStatus st = solve(base, x[1]->sp.p, yb.sp.p, exact, w);
  out.walk_status = st;
  if (st != WalkStatus::ok) return shift_status(st);
  double d0 = 0.0, d1 = 0.0;
  if (manifold_shift_jacobian(exact, w.chain, out.end_jacobian) != WalkStatus::ok ||
      start_density(exact, d0) != WalkStatus::ok || start_density(w.chain, d1) != WalkStatus::ok)
    return ShiftStatus::not_invertible;
  out.start_density = d1 / d0;

  // The offset's chain re-traced in float from y_b through the walked positions (rays
  // leave from the vertex itself, pathspace/scatter.h): full SurfaceHits, and visibility.
  const double tol = 1e-4 * std::max(1.0, double(scene.scene_radius()));
  scene::SurfaceHit from = pathspace::surface_hit(yb);
  for (int j = 1; j <= m; ++j) {
    const Vec3d target = j < m ? w.chain.v[size_t(m - j)].p() : d3(x[size_t(m)]->sp.p);
    const Vec3 dir = (target.cast<float>() - from.p).normalized();
    const auto hit = scene.trace_from(from, dir);
    const int32_t shape = j < m ? x[size_t(j)]->shape : c->shape;  // a light endpoint's from pinned()
    if (!hit || hit->shape != shape || !((d3(hit->p) - target).norm() <= tol)) return ShiftStatus::occluded;
    if (j == m) break;
    out.steps.push_back(ChainStep{*hit});
    from = *hit;
  }
  // The base's Dirac lobes replayed at the offset's vertices from the base's sampling
  // side (camera walk: wi toward y_{k-1}; light walk: wi toward y_{k+1}).
  for (int j = 1; j < m; ++j) {
    ChainStep& s = out.steps[size_t(j - 1)];
    const Vec3 prev = j == 1 ? yb.sp.p : out.steps[size_t(j - 2)].hit.p;
    const Vec3 next = j + 1 == m ? x[size_t(m)]->sp.p : out.steps[size_t(j)].hit.p;
    const Vec3 to_prev = (prev - s.hit.p).normalized(), to_next = (next - s.hit.p).normalized();
    const Vec3 wi = mode == scene::TransportMode::radiance ? to_prev : to_next;
    const Vec3 wo = mode == scene::TransportMode::radiance ? to_next : to_prev;
    if (!s.hit.bsdf) return ShiftStatus::zero_contribution;
    const Vec3 wi_l = s.hit.shading.to_local(wi), wo_l = s.hit.shading.to_local(wo);
    if (!pathspace::consistent_side(s.hit, wi, wi_l.z()) || !pathspace::consistent_side(s.hit, wo, wo_l.z()))
      return ShiftStatus::zero_contribution;
    const BidirVertex& xb = *x[size_t(j)];
    const auto bs = pathspace::sample_dirac_lobe(*s.hit.bsdf, scene::BsdfContext{s.hit.uv, mode}, wi_l, xb.lobe,
                                                 xb.u_lobe);
    if (!bs || !(bs->pdf > 0.0f) || is_black(bs->weight) || (bs->wo - wo_l).norm() > 1e-3f)
      return ShiftStatus::zero_contribution;
    s.weight = bs->weight;
    s.pdf = bs->pdf;
  }

  // Invertibility: the reverse shift walks the offset's own float chain back to x_b and
  // must find the base's chain, not another solution with the same ends.
  // Same shapes, interaction types and etas as the base's chain (the replay checked them).
  for (int j = 1; j < m; ++j) {
    ChainVertex& v = inner[size_t(j - 1)];
    const auto y = manifold::make_vertex(scene, out.steps[size_t(j - 1)].hit, v.type, v.eta);
    if (!y) return ShiftStatus::not_invertible;
    v = *y;
  }
  Chain offset, back_exact;
  manifold::WalkResult back;
  if (!build_chain(scene, *c, inner, pathspace::surface_hit(yb), offset)) return ShiftStatus::not_invertible;
  st = solve(offset, out.steps[0].hit.p, x[0]->sp.p, back_exact, back);
  const double back_tol = settings.reverse_tolerance * std::max(1e-3, double(scene.scene_radius()));
  for (int i = 1; st == WalkStatus::ok && i < exact.n(); ++i)
    if (!((back.chain.v[size_t(i)].p() - exact.v[size_t(i)].p()).norm() <= back_tol)) st = WalkStatus::not_reversible;
  if (st != WalkStatus::ok) {
    out.walk_status = WalkStatus::not_reversible;
    return ShiftStatus::not_invertible;
  }
  out.walk_status = WalkStatus::ok;
  return ShiftStatus::ok;
}

}  // namespace dp::gradients
