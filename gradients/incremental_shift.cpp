#include "gradients/incremental_shift.h"

#include <algorithm>
#include <cmath>

#include "gradients/manifold_shift.h"  // shift_status(WalkStatus)
#include "gradients/shift_helpers.h"
#include "manifold/local_geometry.h"
#include "pathspace/classify.h"

namespace dp::gradients {

using manifold::ChainVertex;
using manifold::WalkStatus;
using pathspace::Path;
using pathspace::Vertex;
using pathspace::VertexKind;

OcclusionDecision symmetric_threshold(std::function<float(const Vec3&)> coefficient, float threshold) {
  return [c = std::move(coefficient), threshold](const Vec3& a, const Vec3& b) {
    return c(a) > threshold && c(b) > threshold;  // symmetric in (a, b) by construction
  };
}

bool incremental_direction_factors(const std::vector<ChainVertex>& base, const manifold::IncrementalResult& result,
                                   std::vector<double>& factors) {
  const int r = result.reconnect;
  if (r < 1 || size_t(r) >= base.size() || result.offset.size() != base.size()) return false;
  factors.assign(size_t(r), 1.0);
  // d w_j = |cos theta_{j+1}| / d_j^2 dA_{j+1} for base and offset (y~_r = y_r).
  auto density = [](const ChainVertex& a, const ChainVertex& c) {
    const Vec3d d = c.p() - a.p();
    const double d2 = d.squaredNorm();
    return d2 > 0.0 ? std::abs(c.f.ng.dot(d)) / (std::sqrt(d2) * d2) : 0.0;
  };
  for (int j = 0; j < r; ++j) {
    const double gb = density(base[size_t(j)], base[size_t(j + 1)]);
    const double go = density(result.offset[size_t(j)], j + 1 < r ? result.offset[size_t(j + 1)] : base[size_t(j + 1)]);
    if (!(gb > 0.0) || !(go > 0.0)) return false;
    factors[size_t(j)] = go / gb;
  }
  factors[size_t(r - 1)] *= result.jacobian;  // the area map of the declared vertices
  return std::isfinite(factors[size_t(r - 1)]) && factors[size_t(r - 1)] > 0.0;
}

bool IncrementalManifoldShift::declarable(const Vertex& v) const {
  return v.kind == VertexKind::surface && v.hit.bsdf && !v.hit.emitter && v.connectable;
}

bool IncrementalManifoldShift::applies(const Path& base, int k, const ShiftResult& out) const {
  // Exactly where ReconnectionShift::step would reconnect to x_{k+1} (a surface).
  if (k < 1 || k + 1 >= base.size() || out.reconnected >= 0 || out.path.size() != k + 1) return false;
  const Vertex &b = base[k], &bn = base[k + 1], &ov = out.path[k];
  return b.connectable && !b.delta_lobe() && ov.kind == VertexKind::surface && ov.hit.bsdf && ov.connectable &&
         wi_consistent(ov) && bn.connectable && bn.kind == VertexKind::surface;
}

void IncrementalManifoldShift::shift(const Path& base, const Vec2& raster_offset, ShiftResult& out) const {
  ReconnectionShift::shift(base, raster_offset, out);
  drop_declared_nee(out);
}

void drop_declared_nee(ShiftResult& out) {
  // The declared vertices are y_1 .. y_{r-1} = x_{c - declared} .. x_{c-1}, c = reconnected.
  if (out.declared <= 0 || out.reconnected <= 0) return;
  for (int k = std::max(1, out.reconnected - out.declared); k < out.alive && k < out.reconnected; ++k) {
    out.path.nee[size_t(k)] = pathspace::LightSample();
    out.nee_status[size_t(k)] = ShiftStatus::not_invertible;
    out.nee_step[size_t(k)] = StepKind::none;
    out.nee_jacobian[size_t(k)] = 1.0;
  }
}

std::optional<ShiftStatus> IncrementalManifoldShift::declared_step(const Path& base, int k, ShiftResult& out) const {
  if (!applies(base, k, out) || !declarable(base[k + 1]) || !m_decide(base[k].p(), out.path[k].p()))
    return std::nullopt;
  return walk_vertices(base, k, out);
}

ShiftStatus IncrementalManifoldShift::step(const Path& base, int k, ShiftResult& out) const {
  if (const auto s = declared_step(base, k, out)) return *s;
  return ReconnectionShift::step(base, k, out);  // y_1 not declared: reconnect at x_{k+1}
}

ShiftStatus IncrementalManifoldShift::walk_vertices(const Path& base, int k, ShiftResult& out) const {
  const int n = base.size();
  Path& o = out.path;
  // y_0 .. y_m: the base's surface vertices from x_k on (an environment vertex ends them).
  int m = k + 1;
  while (m + 1 < n && base[m + 1].kind == VertexKind::surface) ++m;
  std::vector<ChainVertex> chain;
  for (int j = k; j <= m; ++j) {
    const auto cv = manifold::make_vertex(m_scene, base[j].hit, manifold::Interaction::reflection);
    if (!cv) {
      if (j <= k + 1) return ShiftStatus::not_invertible;
      m = j - 1;
      break;
    }
    chain.push_back(*cv);
  }
  const auto start = manifold::make_vertex(m_scene, o[k].hit, manifold::Interaction::reflection);
  if (!start) return ShiftStatus::not_invertible;
  for (int j = k; j < m; ++j) out.step[size_t(j)] = StepKind::manifold;

  // decide(i, y_{i-1}, y~_{i-1}) (header): float positions, as the reverse shift sees them.
  const auto declare = [&](int i, const ChainVertex& bp, const ChainVertex& op) {
    if (m_inc.max_declared > 0 && i > m_inc.max_declared) return false;
    if (!declarable(base[k + i])) return false;
    const Vec3 a = i == 1 ? base[k].p() : bp.p().cast<float>();
    const Vec3 b = i == 1 ? o[k].p() : op.p().cast<float>();
    return m_decide(a, b);
  };
  manifold::WalkStats ws;
  const manifold::IncrementalResult res = manifold::incremental_walk(m_scene, chain, *start, declare, m_inc.walk, &ws);
  out.walk_status = int(res.status);
  out.walk_traces = ws.traces;
  for (int b = 0; b < manifold::WalkStats::kIterationBins; ++b) out.walk_iterations += int(b * ws.iterations[size_t(b)]);
  if (!res.ok()) return shift_status(res.status);
  const int r = res.reconnect;
  // A declared vertex without a pin (the path ends or escapes after it), or one whose base
  // lobe refracts (the walk keeps reflection half vectors), has no offset here.
  if (r == m - k && declare(r, chain[size_t(r - 1)], res.offset[size_t(r - 1)])) return ShiftStatus::not_invertible;
  for (int i = 1; i < r; ++i)
    if (is_refraction(base[k + i])) return ShiftStatus::not_invertible;

  const double scale = std::max(1.0, double(m_scene.scene_radius()));
  if (m_inc.check_reverse && r > 1) {
    // The reverse shift's own incremental walk from the offset back to y_0 (header).
    std::vector<ChainVertex> back_base = res.offset;
    const auto back_declare = [&](int i, const ChainVertex& bp, const ChainVertex& op) {
      return declare(i, op, bp);  // roles swapped; declare is symmetric in its positions
    };
    const auto back = manifold::incremental_walk(m_scene, back_base, chain[0], back_declare, m_inc.walk, &ws);
    out.walk_traces = ws.traces;
    bool same = back.ok() && back.reconnect == r;
    const double tol = m_inc.walk.reverse_tolerance * std::max(1e-3, double(m_scene.scene_radius()));
    for (int i = 1; same && i < r; ++i) same = (back.offset[size_t(i)].p() - chain[size_t(i)].p()).norm() <= tol;
    if (!same) {
      out.walk_status = int(WalkStatus::not_reversible);
      return ShiftStatus::not_invertible;
    }
  }
  std::vector<double> factors;
  if (!incremental_direction_factors(chain, res, factors)) return ShiftStatus::not_invertible;

  // Offset vertices y~_1 .. y~_{r-1} re-traced in float from y~_0, then the reconnection.
  const auto scatter_to = [&](int j, const Vec3& dir) -> ShiftStatus {
    Vertex& ov = o[j];
    const Vertex& b = base[j];
    if (ov.kind != VertexKind::surface || !ov.hit.bsdf || !wi_consistent(ov)) return ShiftStatus::zero_contribution;
    const auto ctx = pathspace::radiance_context(ov.hit);
    const Vec3 wo_l = ov.hit.shading.to_local(dir);
    if (!pathspace::consistent_side(ov.hit, dir, wo_l.z())) return ShiftStatus::zero_contribution;
    if (b.delta_lobe()) {  // a declared vertex whose base took a Dirac lobe: the walk kept it
      const auto bs = pathspace::sample_dirac_lobe(*ov.hit.bsdf, ctx, ov.wi, b.lobe, b.u_lobe);
      if (!bs || !(bs->pdf > 0.0f) || (bs->wo - wo_l).norm() > 1e-3f) return ShiftStatus::zero_contribution;
      set_scatter(ov, b, wo_l, dir, bs->weight * bs->pdf, double(bs->pdf));
      ov.eta = bs->eta;
      return ShiftStatus::ok;
    }
    float p = 0.0f;
    const Rgb f = ov.hit.bsdf->eval_pdf(ctx, ov.wi, wo_l, p) * abs_cos_theta(wo_l);
    if (!(p > 0.0f)) return ShiftStatus::zero_contribution;
    set_scatter(ov, b, wo_l, dir, f, double(p));
    return ShiftStatus::ok;
  };
  const double tol = 1e-4 * scale;
  for (int i = 1; i < r; ++i) {
    const int j = k + i;
    const Vec3d target = res.offset[size_t(i)].p();
    const Vec3 dir = (target.cast<float>() - o[j - 1].p()).normalized();
    const ShiftStatus ss = scatter_to(j - 1, dir);
    if (ss != ShiftStatus::ok) return ss;
    const auto hit = m_scene.trace_from(o[j - 1].hit, dir);
    if (!hit || hit->shape != base[j].hit.shape || !((d3(hit->p) - target).norm() <= tol)) return ShiftStatus::occluded;
    Vertex nv;
    nv.kind = VertexKind::surface;
    nv.hit = *hit;
    nv.connectable = pathspace::is_connectable(hit->bsdf, m_opt.threshold);
    nv.wi = hit->shading.to_local(-dir);
    nv.emission = pathspace::emitted(m_scene, nv, -dir);
    o.append(nv);
  }
  const int c = k + r;  // the reconnection x'_{c-1} -> x_c
  const Vertex& bc = base[c];
  if (m_scene.occluded(m_scene.spawn_segment(o[c - 1].hit, bc.p()))) return ShiftStatus::occluded;
  const Vec3 dir = (bc.p() - o[c - 1].p()).normalized();
  const ShiftStatus ss = scatter_to(c - 1, dir);
  if (ss != ShiftStatus::ok) return ss;
  Vertex nv = bc;
  nv.wi = nv.hit.shading.to_local(-dir);
  nv.emission = pathspace::emitted(m_scene, nv, -dir);
  o.append(nv);
  for (int j = k; j < m; ++j) out.step[size_t(j)] = j < c ? StepKind::manifold : StepKind::none;
  for (int i = 0; i < r; ++i) out.jacobian[size_t(k + i)] = reported_jacobian(factors[size_t(i)], m_opt.fault, false);
  out.reconnected = c;
  out.declared = r - 1;
  return ShiftStatus::ok;
}

}  // namespace dp::gradients
