#include "manifold/walk.h"

#include <algorithm>
#include <cmath>

#include "manifold/constraints.h"
#include "manifold/local_geometry.h"

namespace dp::manifold {

namespace {

constexpr double kGrazingRay = 1e-9;

double walk_scale(const Chain& c, const Vec3d& target) {
  return std::max(target.cwiseAbs().maxCoeff(), (target - c.v[size_t(c.n() - 1)].p()).norm());
}

// |x_n - target| in the end's tangent plane: the target (a float hit point) may lie off
// the end's surface by round-off, a distance no walk can reduce.
double end_distance(const Chain& c, const Vec3d& target) {
  const ChainVertex& end = c.v[size_t(c.n())];
  const Vec3d d = target - end.p();
  return (d - d.dot(end.f.ng) * end.f.ng).norm();
}

}  // namespace

// Inverse of the constraint of constraints.h.
WalkStatus scatter(const ChainVertex& v, const Vec3d& w_a, Vec3d& w_b) {
  const Vec2d& c = v.target;
  const double c2 = c.squaredNorm();
  if (!(c2 < 1.0)) return WalkStatus::grazing;
  const Vec3d m = c.x() * v.f.s + c.y() * v.f.t + std::sqrt(1.0 - c2) * v.f.n;
  const double ca = w_a.dot(v.f.ng);
  if (std::abs(ca) < kGrazingRay) return WalkStatus::grazing;
  if (v.type == Interaction::reflection) {
    w_b = 2.0 * w_a.dot(m) * m - w_a;  // reflection about m (sign of m irrelevant)
  } else {
    if (v.eta == 1.0) return WalkStatus::index_matched;
    const double eta_a = ca > 0 ? 1.0 : v.eta, eta_b = ca > 0 ? v.eta : 1.0;
    const Vec3d mf = w_a.dot(m) >= 0 ? m : Vec3d(-m);
    const double cos_i = w_a.dot(mf);
    const double eta = eta_a / eta_b;
    const double sin2_t = eta * eta * std::max(0.0, 1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return WalkStatus::total_internal_reflection;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    // eta_a w_a + eta_b w_b is parallel to m (Walter et al. 2007, Eq. 16).
    w_b = -eta * w_a + (eta * cos_i - cos_t) * mf;
  }
  const double norm = w_b.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return WalkStatus::grazing;
  w_b /= norm;
  const double cb = w_b.dot(v.f.ng);
  if (std::abs(cb) < kGrazingRay) return WalkStatus::grazing;
  const bool same_side = ca * cb > 0;
  if (same_side != (v.type == Interaction::reflection)) return WalkStatus::grazing;
  return WalkStatus::ok;
}

WalkStatus retrace(const scene::Scene& scene, const Chain& base, const Vec3d& x1, Chain& out) {
  const int n = base.n();
  if (n < 2) return WalkStatus::invalid_input;
  if (!x1.allFinite()) return WalkStatus::invalid_input;
  out = base;
  Vec3d origin, dir, ng_origin = Vec3d::Zero();
  if (base.pin == Pin::direction) {
    dir = base.start_dir;
    const double back =
        (x1 - scene.bounds().center().cast<double>()).norm() + 2.0 * double(scene.scene_radius()) + 1.0;
    origin = x1 - back * dir;
    out.v[0].f.p = origin;
  } else {
    origin = base.v[0].p();
    const Vec3d d = x1 - origin;
    const double len = d.norm();
    if (!(len > 0.0)) return WalkStatus::invalid_input;
    dir = d / len;
    if (base.v[0].has_surface) ng_origin = base.v[0].f.ng;
  }
  for (int i = 1; i <= n; ++i) {
    if (i == n && base.end_plane) {  // the virtual plane of a medium end (chain.h)
      ChainVertex& e = out.v[size_t(n)];
      const double dn = dir.dot(e.f.n);
      if (std::abs(dn) < kGrazingRay) return WalkStatus::grazing;
      const double t = (e.f.p - origin).dot(e.f.n) / dn;
      if (!(t > 0.0) || !std::isfinite(t)) return WalkStatus::miss;
      e.f.p = origin + t * dir;
      break;
    }
    const auto hit = trace(scene, origin, dir, ng_origin);
    if (!hit) return WalkStatus::miss;
    ChainVertex& v = out.v[size_t(i)];
    if (hit->shape != base.v[size_t(i)].shape) return WalkStatus::different_object;
    if (!local_frame(*scene.shapes()[size_t(hit->shape)], hit->prim, hit->p, v.f)) return WalkStatus::singular;
    v.prim = hit->prim;
    if (i == n) break;
    Vec3d w_b;
    const WalkStatus st = scatter(v, -dir, w_b);
    if (st != WalkStatus::ok) return st;
    origin = v.p();
    dir = w_b;
    ng_origin = v.f.ng;
  }
  return WalkStatus::ok;
}

WalkResult walk(const scene::Scene& scene, const Chain& chain, const Vec3d& target, const WalkSettings& settings,
                WalkStats* stats) {
  WalkResult r;
  auto finish = [&](WalkStatus st) -> WalkResult {
    r.status = st;
    if (stats) stats->record(st, r.iterations);
    return r;
  };
  if (chain.n() < 2 || !target.allFinite()) return finish(WalkStatus::invalid_input);
  // Start from the chain re-traced through its own x_1, so the current chain satisfies
  // its constraints exactly (inputs from float paths do so only to ~1e-6).
  WalkStatus st = WalkStatus::ok;
  if (settings.exact_input) {
    r.chain = chain;
  } else {
    st = retrace(scene, chain, chain.v[1].p(), r.chain);
    if (stats) ++stats->traces;
    if (st != WalkStatus::ok) return finish(st);
  }
  const int n = chain.n();
  const double scale = walk_scale(r.chain, target);
  r.distance = end_distance(r.chain, target);
  double step = 1.0;
  Chain trial;
  std::vector<Mat2d> T;
  bool need_map = true;
  WalkStatus last_failure = WalkStatus::max_iterations;
  while (true) {
    if (r.distance < std::max(settings.tolerance * scale, settings.accept_distance)) break;
    if (r.iterations >= settings.max_iterations) return finish(last_failure);
    if (need_map) {
      st = tangent_map(r.chain, T);
      if (st != WalkStatus::ok) return finish(st);
      need_map = false;
    }
    // Newton step: end displacement in the end's tangent plane, mapped to x_1.
    const ChainVertex& end = r.chain.v[size_t(n)];
    const Vec3d delta = target - end.p();
    const Vec2d d_end(delta.dot(end.f.T1), delta.dot(end.f.T2));
    const Vec2d d1 = T[1] * d_end;
    const ChainVertex& x1 = r.chain.v[1];
    const Vec3d x1_new = x1.p() + step * (d1.x() * x1.f.T1 + d1.y() * x1.f.T2);
    ++r.iterations;
    st = retrace(scene, r.chain, x1_new, trial);
    if (stats) ++stats->traces;
    const double dist = st == WalkStatus::ok ? end_distance(trial, target) : 0.0;
    if (st == WalkStatus::ok && dist < r.distance) {
      std::swap(r.chain, trial);
      r.distance = dist;
      step = std::min(1.0, 2.0 * step);
      need_map = true;
      last_failure = WalkStatus::max_iterations;
    } else {
      last_failure = st == WalkStatus::ok ? WalkStatus::max_iterations : st;
      step *= 0.5;
      if (step < settings.min_step) return finish(st == WalkStatus::ok ? WalkStatus::step_too_small : st);
    }
  }
  if (settings.check_reversible) {
    st = check_reversible(scene, chain, r.chain, settings, nullptr);
    if (st != WalkStatus::ok) return finish(st);
  }
  return finish(WalkStatus::ok);
}

WalkStatus walk_exact(const scene::Scene& scene, const Chain& chain, const Vec3d& x_next, const Vec3d& target,
                      const WalkSettings& settings, Chain& exact, WalkResult& w, WalkStats& stats) {
  Chain rev = chain;
  std::reverse(rev.v.begin(), rev.v.end());
  const WalkStatus st = retrace(scene, rev, x_next, exact);
  ++stats.traces;
  if (st != WalkStatus::ok) {
    stats.record(st, 0);
    return st;
  }
  std::reverse(exact.v.begin(), exact.v.end());  // pinned at the re-traced start, ending at x_n
  w = walk(scene, exact, target, settings, &stats);
  return w.status;
}

WalkStatus check_reversible(const scene::Scene& scene, const Chain& original, const Chain& walked,
                            const WalkSettings& settings, WalkStats* stats) {
  WalkSettings back = settings;
  back.check_reversible = false;
  const WalkResult r = walk(scene, walked, original.v.back().p(), back, stats);
  if (!r.ok()) return WalkStatus::not_reversible;
  const double tol = settings.reverse_tolerance * std::max(1e-3, double(scene.scene_radius()));
  for (size_t i = 1; i < original.v.size(); ++i)
    if (!((r.chain.v[i].p() - original.v[i].p()).norm() <= tol)) return WalkStatus::not_reversible;
  return WalkStatus::ok;
}

}  // namespace dp::manifold
