#include "manifold/incremental.h"

#include <cmath>

#include "manifold/constraints.h"

namespace dp::manifold {

namespace {

// Triple chain for step i: pinned y_{i+1}, interior y_i, movable end y_{i-1}.
Chain triple(const ChainVertex& next, const ChainVertex& mid, const ChainVertex& prev) {
  Chain c;
  c.pin = Pin::position;
  c.v = {next, mid, prev};
  return c;
}

}  // namespace

IncrementalResult incremental_walk(const scene::Scene& scene, const std::vector<ChainVertex>& base,
                                   const ChainVertex& new_start, const SpecularDecision& decide,
                                   const WalkSettings& settings, WalkStats* stats) {
  IncrementalResult r;
  const int m = int(base.size()) - 1;
  if (m < 1) return r;
  r.offset = base;
  r.offset[0] = new_start;
  // Per declared step: base blocks (a, b, c) and offset blocks (b~, c~) in the forward
  // orientation (a: w.r.t. y_{i-1}, c: w.r.t. y_{i+1}).
  std::vector<Mat2d> A, B, C, Bt, Ct;
  int i = 1;
  for (; i < m; ++i) {
    if (!decide(i, base[size_t(i - 1)], r.offset[size_t(i - 1)])) break;
    Chain bc = triple(base[size_t(i + 1)], base[size_t(i)], base[size_t(i - 1)]);
    bc.v[1].type = base[size_t(i)].type;
    WalkStatus st = set_targets_from_current(bc);
    Blocks bb;
    if (st == WalkStatus::ok) st = derivative_blocks(bc, bb);
    if (st != WalkStatus::ok) {
      r.status = st;
      return r;
    }
    const WalkResult w = walk(scene, bc, r.offset[size_t(i - 1)].p(), settings, stats);
    if (!w.ok()) {
      r.status = w.status;
      return r;
    }
    Blocks ob;
    st = derivative_blocks(w.chain, ob);
    if (st != WalkStatus::ok) {
      r.status = st;
      return r;
    }
    // The walked end lies on y_{i-1}'s surface at y~_{i-1}: keep y~_{i-1} itself.
    r.offset[size_t(i)] = w.chain.v[1];
    // Reversed chain: its "a" is w.r.t. y_{i+1}, its "c" w.r.t. y_{i-1}.
    A.push_back(bb.c[1]);
    B.push_back(bb.b[1]);
    C.push_back(bb.a[1]);
    Bt.push_back(ob.b[1]);
    Ct.push_back(ob.a[1]);
    r.per_step_product *= std::abs(bb.b[1].determinant()) / std::abs(ob.b[1].determinant());
  }
  r.reconnect = i;
  // |det R| / prod |det b~_i| (see header).
  const size_t steps = B.size();
  double det_r = 1, det_bt = 1;
  Mat2d D = Mat2d::Zero(), U = Mat2d::Zero();
  for (size_t s = 0; s < steps; ++s) {
    D = s == 0 ? B[0] : Mat2d(B[s] - A[s] * U);
    const double d = D.determinant();
    if (!std::isfinite(d) || !(std::abs(d) > 1e-12 * D.squaredNorm())) {
      r.status = WalkStatus::singular;
      return r;
    }
    det_r *= d;
    det_bt *= Bt[s].determinant();
    if (s + 1 < steps) U = D.inverse() * (C[s] - Ct[s]);
  }
  r.jacobian = steps == 0 ? 1.0 : std::abs(det_r) / std::abs(det_bt);
  r.status = std::isfinite(r.jacobian) && std::isfinite(r.per_step_product) ? WalkStatus::ok : WalkStatus::singular;
  return r;
}

}  // namespace dp::manifold
