#include "mcmc/mut_manifold.h"

#include <algorithm>
#include <cmath>

#include "core/vmf.h"
#include "mcmc/perturb_chain.h"
#include "pathspace/bidir_light.h"

namespace dp::mcmc {

using pathspace::BidirKind;
using pathspace::BidirVertex;
using scene::TransportMode;

namespace {

TransportMode walk_mode(int step) { return step < 0 ? TransportMode::radiance : TransportMode::importance; }

// The next smooth vertex after i in direction step (-1 or K + 1 past the ends).
int next_smooth(const PathState& s, int i, int step) {
  int j = i + step;
  while (j >= 0 && j <= s.depth() && s.v[size_t(j)].delta) j += step;
  return j;
}

bool finite_light(const BidirVertex& v) {
  const auto k = v.emitter->kind();
  return k == scene::EmitterKind::area || k == scene::EmitterKind::point || k == scene::EmitterKind::spot;
}

// Where b connects to c directly (no chain between them): is the segment free?
bool segment_free(const scene::Scene& scene, const BidirVertex& u, const BidirVertex& v) {
  if (u.on_surface()) return !scene.occluded(scene.spawn_segment(u.sp, v.sp.p));
  if (v.on_surface()) return !scene.occluded(scene.spawn_segment(v.sp, u.sp.p));
  return !scene.occluded(u.sp.p, v.sp.p);
}

// |cos| at u toward v times 1/d^2 ... J_uv = d w_u / dA_v = |cos_v| / d^2 (no chain).
double direct_jacobian(const BidirVertex& u, const BidirVertex& v) {
  const Vec3 d = v.sp.p - u.sp.p;
  const double d2 = double(d.squaredNorm());
  if (!(d2 > 0.0)) return 0.0;
  const double c = v.on_surface() ? std::abs(double(v.sp.ng.dot(d))) / std::sqrt(d2) : 1.0;
  return c / d2;
}

}  // namespace

ManifoldPerturbation::ManifoldPerturbation(const scene::Scene& scene, const ManifoldSettings& settings)
    : m_scene(scene), m_opt(settings) {}

bool ManifoldPerturbation::eligible_start(const PathState& s, int i) const {
  const BidirVertex& v = s.v[size_t(i)];
  if (v.delta) return false;
  if (v.kind == BidirKind::camera) return true;
  if (v.kind == BidirKind::light) return finite_light(v);
  return v.bsdf && !v.bsdf->is_purely_delta();
}

bool ManifoldPerturbation::valid_start(const PathState& s, int a, int step, int& b, int& c) const {
  const int K = s.depth();
  if (!eligible_start(s, a)) return false;
  b = next_smooth(s, a, step);
  if (b < 0 || b > K || s.v[size_t(b)].kind != BidirKind::surface) return false;
  c = next_smooth(s, b, step);
  if (c < 0 || c > K) return false;
  const BidirVertex& vc = s.v[size_t(c)];
  return vc.kind != BidirKind::camera && !vc.infinite() && (std::abs(c - b) < 2 || gradients::chain_end(vc));
}

double ManifoldPerturbation::start_pmf(const PathState& s, int a, int step) const {
  const int K = s.depth();
  int b = 0, c = 0, n = 0;
  for (int i = 0; i <= K; ++i)
    for (int d : {-1, 1}) n += valid_start(s, i, d, b, c);
  const double sensor = valid_start(s, K, -1, b, c) ? m_opt.sensor_prob : 0.0;
  double p = (a == K && step == -1) ? sensor : 0.0;
  if (n > 0 && valid_start(s, a, step, b, c)) p += (1.0 - sensor) / double(n);
  return p;
}

double ManifoldPerturbation::leave_density(const PathState& s, int i, int step) const {
  const BidirVertex& v = s.v[size_t(i)];
  const Vec3 wo = direction_between(v, s.v[size_t(i + step)]);
  if (v.kind == BidirKind::camera) return double(m_scene.camera().pdf_direction(wo));
  if (v.kind == BidirKind::light) return double(pathspace::light_pdf_dir(v, wo));
  return double(pathspace::bsdf_pdf(v, direction_between(v, s.v[size_t(i - step)]), wo, walk_mode(step)));
}

double ManifoldPerturbation::kappa(const PathState& s, int a, int step) const {
  const double peak = m_opt.lambda * m_opt.lambda * std::max(1.0 / (4.0 * kPiD), leave_density(s, a, step));
  return 2.0 * kPiD * peak;
}

ProposalStatus ManifoldPerturbation::sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                            PathSides& sides) const {
  const int K = x.depth();
  // 1. (a, step) among the starts whose b and c exist (start_pmf), then b and c.
  int a = K, step = -1, b = 0, c = 0;
  const double sensor = valid_start(x, K, -1, b, c) ? m_opt.sensor_prob : 0.0;
  if (!(rng.uniform_double() < sensor)) {
    std::vector<std::pair<int, int>> starts;
    for (int i = 0; i <= K; ++i)
      for (int d : {-1, 1})
        if (valid_start(x, i, d, b, c)) starts.emplace_back(i, d);
    if (starts.empty()) return ProposalStatus::no_choice;
    const auto pick = starts[std::min(size_t(rng.uniform_double() * double(starts.size())), starts.size() - 1)];
    a = pick.first;
    step = pick.second;
  }
  valid_start(x, a, step, b, c);
  const BidirVertex& xc = x.v[size_t(c)];
  const bool chain = std::abs(c - b) >= 2;
  // The strategy whose walk covers a .. c in this direction (path_state.h's C_s).
  int s = -1;
  if (step < 0) {
    for (int t = c; t >= 0 && s < 0; --t)
      if (x.inv_c[size_t(t)] > 0.0) s = t;
  } else {
    for (int t = c + 1; t <= K && s < 0; ++t)
      if (x.inv_c[size_t(t)] > 0.0) s = t;
  }
  if (s < 0) return ProposalStatus::no_choice;
  rec.a = a, rec.b = b, rec.c = c, rec.step = step, rec.strategy = s;
  rec.jacobian = 1.0;
  // 2. The new direction at a.
  const Vec3 w_old = direction_between(x.v[size_t(a)], x.v[size_t(a + step)]);
  double cos_t = 1, phi = 0;
  core::vmf_sample(kappa(x, a, step), rng.uniform_double(), rng.uniform_double(), cos_t, phi);
  const Vec3 w = turn_direction(w_old, cos_t, phi);
  // 3. a -> b re-traced, b .. c walked.
  y.v = x.v;
  ProposalStatus st = retrace_chain(m_scene, x, y.v, a, b, w, walk_mode(step));
  if (st != ProposalStatus::ok) return st;
  if (chain) {
    std::vector<const BidirVertex*> cx;
    for (int i = b;; i += step) {
      cx.push_back(&x.v[size_t(i)]);
      if (i == c) break;
    }
    gradients::BidirChainWalk walk;
    if (gradients::walk_bidir_chain(m_scene, cx, y.v[size_t(b)], TransportMode::radiance, m_opt.walk, walk) !=
        gradients::ShiftStatus::ok)
      return ProposalStatus::chain_walk;
    for (size_t j = 0; j < walk.steps.size(); ++j) {
      const int i = b + step * int(j + 1);
      BidirVertex v = pathspace::surface_vertex_at(walk.steps[j].hit);
      const BidirVertex& old = x.v[size_t(i)];
      v.delta = true;
      v.lobe = old.lobe;
      v.u_lobe = old.u_lobe;
      v.wi = direction_between(v, y.v[size_t(i - step)]);
      y.v[size_t(i)] = v;
    }
    rec.jacobian = walk.end_jacobian;
  } else if (!segment_free(m_scene, y.v[size_t(b)], xc)) {
    return ProposalStatus::occluded;
  }
  rec.cos_turn = double(w.dot(w_old));
  const bool valid = evaluate_path(m_scene, y, sides);
  if (y.nonfinite) return ProposalStatus::nonfinite;
  if (!valid) return ProposalStatus::zero;
  if (!(y.inv_c[size_t(s)] > 0.0)) return ProposalStatus::zero;
  return ProposalStatus::ok;
}

double ManifoldPerturbation::ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const {
  const int a = rec.a, b = rec.b, c = rec.c, step = rec.step, s = rec.strategy;
  if (!(x.inv_c[size_t(s)] > 0.0) || !(y.inv_c[size_t(s)] > 0.0)) return 0.0;
  // The walk covers the vertex after c only if the strategy's walk continues past it.
  const bool past_c = step < 0 ? s <= c - 1 : s - 1 >= c + 1;
  const TransportMode mode = walk_mode(step);
  auto density = [&](const PathState& p) {
    double d = leave_density(p, a, step) * dirac_chain_prob(p, a, b, mode) * leave_density(p, b, step) *
               dirac_chain_prob(p, b, c, mode);
    if (past_c) d *= leave_density(p, c, step);
    return d;
  };
  double jac = rec.jacobian;  // J_bc(y) / J_bc(x) from the walk
  if (std::abs(c - b) == 1) {
    const double jx = direct_jacobian(x.v[size_t(b)], x.v[size_t(c)]), jy = direct_jacobian(y.v[size_t(b)], y.v[size_t(c)]);
    jac = jx > 0.0 ? jy / jx : 0.0;
  }
  const double fwd = y.inv_c[size_t(s)] * density(x) * core::vmf_pdf(kappa(x, a, step), rec.cos_turn) * start_pmf(x, a, step);
  const double rev = x.inv_c[size_t(s)] * density(y) * core::vmf_pdf(kappa(y, a, step), rec.cos_turn) * start_pmf(y, a, step) * jac;
  return fwd > 0.0 ? rev / fwd : 0.0;
}

}  // namespace dp::mcmc
