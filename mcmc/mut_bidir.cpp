#include "mcmc/mut_bidir.h"

#include <algorithm>
#include <cmath>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::mcmc {

using pathspace::BidirKind;
using pathspace::BidirVertex;

namespace {

// The walk's record at each kept vertex: wi toward its predecessor in walk order.
void set_walk_directions(std::vector<BidirVertex>& side) {
  for (size_t i = 1; i < side.size(); ++i) side[i].wi = direction_between(side[i], side[i - 1]);
}

}  // namespace

BidirMutation::BidirMutation(const scene::Scene& scene, const BidirLengths& lengths, BidirMutationFault fault)
    : m_scene(scene), m_lengths(lengths), m_fault(fault) {
  for (const auto& e : scene.emitters())
    if (e->is_delta()) m_light_hittable = false;  // a camera walk can never end on every light
}

BidirShape BidirMutation::shape(const PathState& x) const {
  BidirShape sh;
  const int K = x.depth();
  sh.k = K + 2;
  sh.degenerate.assign(size_t(sh.k + 1), 0);
  for (int i = 0; i <= K; ++i) {
    const BidirVertex& v = x.v[size_t(i)];
    // A mutation's kept end must be able to start a walk: not a Dirac component, not the
    // pinhole (regenerated from its supernode), not a light with a delta position or
    // direction or at infinity (regenerated from the light supernode).
    const bool light_fixed = v.kind == BidirKind::light && (v.emitter->is_delta() || v.emitter->is_infinite());
    sh.degenerate[size_t(i + 1)] = v.delta || v.kind == BidirKind::camera || light_fixed;
  }
  sh.light_hittable = m_light_hittable;
  sh.camera_hittable = false;  // a pinhole
  return sh;
}

ProposalStatus BidirMutation::sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                     PathSides& sides) const {
  return sample_choice(x, y, rec.bidir, rng, sides);
}

ProposalStatus BidirMutation::sample_choice(const PathState& x, PathState& y, BidirChoice& rec, core::Rng& rng,
                                            PathSides& sides) const {
  pathspace::IndependentStream stream(rng);
  if (!sample_bidir_choice(shape(x), m_lengths, stream, rec)) return ProposalStatus::no_choice;
  const int K = x.depth(), L = rec.l, M = rec.m - 1;  // x_0..x_{L-1} and x_M..x_K are kept
  const int s = rec.s, t = rec.ka - 1 - s;
  std::vector<BidirVertex>& light = sides.light;
  std::vector<BidirVertex>& camera = sides.camera;
  light.assign(x.v.begin(), x.v.begin() + L);
  set_walk_directions(light);
  if (!pathspace::extend_subpath(m_scene, light, s, scene::TransportMode::importance, rng))
    return ProposalStatus::walk_ended;
  camera.clear();
  for (int i = K; i >= M; --i) camera.push_back(x.v[size_t(i)]);
  set_walk_directions(camera);
  if (!pathspace::extend_subpath(m_scene, camera, t, scene::TransportMode::radiance, rng))
    return ProposalStatus::walk_ended;
  const BidirVertex& end = camera.back();
  const bool light_from_camera = L + s == 0;  // the camera walk generated the light endpoint
  if (t > 0 && end.kind == BidirKind::light && !light_from_camera) return ProposalStatus::escaped;
  if (light_from_camera && !(end.kind == BidirKind::light || (end.emitter && end.emitter->kind() == scene::EmitterKind::area)))
    return ProposalStatus::light_not_found;
  // y = light walk + camera walk reversed; the strategy that made it is (L + s, ...).
  y.v.assign(light.begin(), light.end());
  for (auto it = camera.rbegin(); it != camera.rend(); ++it) y.v.push_back(*it);
  if (light_from_camera) {
    BidirVertex& y0 = y.v[0];
    if (y0.kind == BidirKind::surface) {
      y0.kind = BidirKind::light;
      y0.bsdf = nullptr;
      y0.sp.shading = Frame::from_normal(y0.sp.ng);
    }
  }
  const int strategy = L + s;
  const bool valid = evaluate_path(m_scene, y, sides);
  if (y.nonfinite) return ProposalStatus::nonfinite;
  if (!valid || !(y.inv_c[size_t(strategy)] > 0.0)) return ProposalStatus::zero;
  if (strategy >= 1) {
    pathspace::MisConfig unweighted;
    unweighted.unweighted = true;
    pathspace::Connection c;
    const int t_all = y.depth() + 1 - strategy;
    if (!pathspace::connect(m_scene, sides.light.data(), strategy, sides.camera.data(), t_all, unweighted, c, true))
      return c.occluded ? ProposalStatus::occluded : ProposalStatus::zero;
  }
  return ProposalStatus::ok;
}

double BidirMutation::inverse_weight(const PathState& src, const PathState& dst, const BidirChoice& rec) const {
  const BidirShape sh = shape(src);
  return inverse_weight(sh, sh, dst, rec);
}

double BidirMutation::inverse_weight(const BidirShape& pmf_shape, const BidirShape& range_shape, const PathState& dst,
                                     const BidirChoice& rec) const {
  const double pmf = bidir_choice_pmf(pmf_shape, m_lengths, rec);
  if (!(pmf > 0.0)) return 0.0;
  int s_min = 0, s_max = 0;
  bidir_split_range(range_shape, rec, s_min, s_max);
  if (m_fault == BidirMutationFault::sampled_split_only) s_min = s_max = std::clamp(rec.s, s_min, s_max);
  double sum = 0.0;
  for (int s = s_min; s <= s_max; ++s) {
    const size_t i = size_t(rec.l + s);
    if (i < dst.inv_c.size()) sum += dst.inv_c[i];
  }
  return pmf * sum;
}

double BidirMutation::ratio(const PathState& x, const PathState& y, const MutationRecord& r) const {
  const BidirChoice& rec = r.bidir;
  const double fwd = inverse_weight(x, y, rec);
  BidirChoice back = rec.reverse();
  back.s = rec.s;  // read only by the sampled_split_only fault
  const BidirShape sy = shape(y);
  const double rev = inverse_weight(m_fault == BidirMutationFault::pmf_from_source ? shape(x) : sy, sy, x, back);
  if (!(fwd > 0.0) || !std::isfinite(fwd) || !std::isfinite(rev)) return 0.0;
  return rev / fwd;
}

}  // namespace dp::mcmc
