#include "gradients/manifold_shift.h"

#include <algorithm>
#include <cmath>

#include "gradients/shift_helpers.h"
#include "manifold/constraints.h"
#include "manifold/local_geometry.h"
#include "pathspace/classify.h"

namespace dp::gradients {

using manifold::Chain;
using manifold::WalkStatus;
using pathspace::Path;
using pathspace::Vertex;
using pathspace::VertexKind;

namespace {

// A chain vertex: every condition here depends only on the vertex's shape (material,
// emitter) and its sampled lobe, which base and offset share.
bool specular_chain_vertex(const Vertex& v) {
  return v.kind == VertexKind::surface && v.hit.bsdf && v.hit.bsdf->is_purely_delta() && v.delta_lobe() &&
         !v.hit.emitter && !(is_refraction(v) && v.eta == 1.0f);
}

}  // namespace

ShiftStatus shift_status(WalkStatus s) {
  switch (s) {
    case WalkStatus::ok: return ShiftStatus::ok;
    case WalkStatus::miss:
    case WalkStatus::different_object: return ShiftStatus::occluded;
    default: return ShiftStatus::not_invertible;
  }
}

namespace {

// |cos| at the chain's end (geometric normal) of the segment toward its neighbour.
double end_cosine(const Chain& c) {
  const auto& end = c.v[size_t(c.n())];
  const Vec3d w = (c.v[size_t(c.n() - 1)].p() - end.p()).normalized();
  return std::abs(w.dot(end.f.ng));
}

}  // namespace

WalkStatus manifold_shift_jacobian(const Chain& base, const Chain& offset, double& J) {
  // Jakob & Marschner 2012, Sec. 4.3 (generalized geometry term); Manzi et al. 2015,
  // Sec. 4: d w_b / dA_c = G(b <-> c) / |cos theta_b| for both paths, same c.
  double G0 = 0, G1 = 0;
  WalkStatus st = manifold::generalized_geometry(base, G0);
  if (st != WalkStatus::ok) return st;
  st = manifold::generalized_geometry(offset, G1);
  if (st != WalkStatus::ok) return st;
  const double c0 = end_cosine(base), c1 = end_cosine(offset);
  if (!(G0 > 0.0) || !(c1 > 0.0) || !(c0 > 0.0)) return WalkStatus::grazing;
  J = (G1 / c1) / (G0 / c0);
  return std::isfinite(J) && J > 0.0 ? WalkStatus::ok : WalkStatus::singular;
}

int ManifoldShift::chain_end(const Path& base, int k, const ShiftResult& out) const {
  if (out.reconnected >= 0 || out.path.size() != k + 1) return -1;
  return chain_end(base, k, out.path[k]);
}

int ManifoldShift::chain_end(const Path& base, int k, const Vertex& ob) const {
  const int n = base.size();
  if (k < 1 || k + 2 >= n) return -1;
  const Vertex& b = base[k];
  if (b.kind != VertexKind::surface || ob.kind != VertexKind::surface || !b.connectable || !ob.connectable ||
      b.delta_lobe() || !ob.hit.bsdf || b.hit.shape != ob.hit.shape)
    return -1;
  int m = k + 1;
  for (; m < n && !base[m].connectable; ++m)
    if (!specular_chain_vertex(base[m])) return -1;
  if (m == k + 1 || m >= n || base[m].kind != VertexKind::surface) return -1;
  if (m_emitter_chains_only && !base[m].hit.emitter) return -1;
  return m;
}

bool ManifoldShift::copy_chain(const Path& base, int k, int m, ShiftResult& r) const {
  for (int j = k; j < m; ++j)
    if (ReconnectionShift::step(base, j, r) != ShiftStatus::ok) return false;
  return true;
}

bool ManifoldShift::same_shapes(const Path& base, const ShiftResult& r, int k, int m) {
  if (m >= base.size() || r.path.size() != m + 1) return false;
  for (int j = k + 1; j <= m; ++j) {
    const Vertex &a = base[j], &o = r.path[j];
    if (a.kind != o.kind || a.connectable != o.connectable || (a.kind == VertexKind::surface && a.hit.shape != o.hit.shape))
      return false;
  }
  return true;
}

std::optional<Chain> ManifoldShift::make_chain(const Path& base, int k, int m) const {
  using manifold::Interaction;
  Chain ch;
  ch.pin = manifold::Pin::position;
  auto add = [&](const Vertex& v, Interaction type, double eta) {
    const auto cv = manifold::make_vertex(m_scene, v.hit, type, eta);
    if (cv) ch.v.push_back(*cv);
    return bool(cv);
  };
  if (!add(base[m], Interaction::reflection, 1.0)) return std::nullopt;  // pinned c
  for (int j = m - 1; j > k; --j) {
    const Vertex& v = base[j];
    if (!is_refraction(v)) {
      if (!add(v, Interaction::reflection, 1.0)) return std::nullopt;
      continue;
    }
    // Chain eta = index behind the geometric normal / index in front (manifold/chain.h);
    // Vertex::eta = eta_o / eta_i of the sampled lobe.
    const bool wi_front = v.hit.ng.dot(v.hit.shading.to_world(v.wi)) > 0.0f;
    if (!add(v, Interaction::refraction, wi_front ? double(v.eta) : 1.0 / double(v.eta))) return std::nullopt;
  }
  if (!add(base[k], Interaction::reflection, 1.0)) return std::nullopt;  // the end b
  return ch;
}

void ManifoldShift::shift(const Path& base, const Vec2& raster_offset, ShiftResult& out) const {
  ReconnectionShift::shift(base, raster_offset, out);
  drop_declared_nee(out);
}

ShiftStatus ManifoldShift::step(const Path& base, int k, ShiftResult& out) const {
  // A chain start (header, "Strategy"): the offset's x'_k made, not reconnected, base x_k
  // connectable with a sampled (non-delta) direction toward a vertex that is not.
  const int n = base.size();
  const bool chain_start = k >= 1 && k + 1 < n && out.reconnected < 0 && out.path.size() == k + 1 &&
                           base[k].connectable && !base[k].delta_lobe() && !base[k + 1].connectable &&
                           out.path[k].connectable;
  if (!chain_start) {
    if (m_incremental)
      if (const auto s = m_incremental->declared_step(base, k, out)) return *s;
    return ReconnectionShift::step(base, k, out);
  }
  const int eligible = chain_end(base, k, out);
  if (eligible >= 0 && !m_walk_as_fallback) return walk_chain(base, k, eligible, out);
  int m = k + 1;
  while (m < n && !base[m].connectable) ++m;
  thread_local ShiftResult copy;
  copy = out;
  const bool done = copy_chain(base, k, std::min(m, n - 1), copy);
  const bool stays = done && same_shapes(base, copy, k, m);
  if (!stays && m_walk_as_fallback) {
    if (eligible >= 0) {
      thread_local ShiftResult walked;
      walked = out;
      if (walk_chain(base, k, eligible, walked) == ShiftStatus::ok) {
        std::swap(out, walked);
        return ShiftStatus::ok;
      }
      copy.walk_status = walked.walk_status;  // the copy stands in for the failed walk
      copy.walk_iterations = walked.walk_iterations;
      copy.walk_traces = walked.walk_traces;
      copy.walk_refused = walked.walk_refused;
      out.walk_status = walked.walk_status;
      out.walk_traces = walked.walk_traces;
      out.walk_refused = walked.walk_refused;
    }
    // The copy is the offset only if the reverse shift (from the copy) would not walk.
    // Also when the copy fails later: its prefix up to its own first connectable vertex
    // (e.g. a light the base's chain passed by) is an offset path that contributes.
    if (reverse_walks(copy.path, k, base)) return ShiftStatus::not_invertible;
  } else if (!stays && eligible < 0 && chain_end(copy.path, k, base[k]) >= 0) {
    return ShiftStatus::not_invertible;  // walk always: the reverse shift would walk the copy's chain
  }
  if (!done) return ReconnectionShift::step(base, k, out);  // the shift loop fails where the copy did
  std::swap(out, copy);
  return ShiftStatus::ok;
}

bool ManifoldShift::reverse_walks(const Path& offset, int k, const Path& base) const {
  const int m = chain_end(offset, k, base[k]);
  if (m < 0) return false;
  thread_local ShiftResult r;
  r.reset(offset.size());
  r.path.raster = base.raster;
  for (int j = 0; j <= k; ++j) r.path.append(base[j]);
  return walk_chain(offset, k, m, r) == ShiftStatus::ok;
}

WalkStatus ManifoldShift::solve(const Path& path, int k, int m, const Vec3d& target, manifold::Chain& exact,
                                manifold::WalkResult& w, manifold::WalkStats& ws) const {
  const auto chain = make_chain(path, k, m);
  if (!chain) return WalkStatus::invalid_input;
  return manifold::walk_exact(m_scene, *chain, d3(path[k + 1].p()), target, m_walk, exact, w, ws);
}

ShiftStatus ManifoldShift::walk_chain(const Path& base, int k, int m, ShiftResult& out) const {
  Path& o = out.path;
  for (int j = k; j < m; ++j) out.step[size_t(j)] = StepKind::manifold;
  if (!wi_consistent(o[k])) return ShiftStatus::zero_contribution;
  manifold::WalkStats ws;
  manifold::Chain exact;
  manifold::WalkResult w;
  WalkStatus st = solve(base, k, m, d3(o[k].p()), exact, w, ws);
  out.walk_status = int(st);
  out.walk_iterations = w.iterations;
  out.walk_traces = ws.traces;
  if (st != WalkStatus::ok) return shift_status(st);
  double J = 0;
  if (manifold_shift_jacobian(exact, w.chain, J) != WalkStatus::ok) return ShiftStatus::not_invertible;

  // Offset vertices along the walked chain, re-traced in float from b' (rays leave from
  // the vertex itself, pathspace/scatter.h) so they carry full SurfaceHits.
  const double tol = 1e-4 * std::max(1.0, double(m_scene.scene_radius()));
  const auto scatter_to = [&](int j, const Vec3& dir) -> ShiftStatus {
    Vertex& ov = o[j];
    const Vertex& b = base[j];
    if (!ov.hit.bsdf) return ShiftStatus::zero_contribution;
    const auto ctx = pathspace::radiance_context(ov.hit);
    const Vec3 wo_l = ov.hit.shading.to_local(dir);
    if (!pathspace::consistent_side(ov.hit, dir, wo_l.z())) return ShiftStatus::zero_contribution;
    if (j == k) {
      float p = 0.0f;
      const Rgb f = ov.hit.bsdf->eval_pdf(ctx, ov.wi, wo_l, p) * abs_cos_theta(wo_l);
      const double pdf = double(p);
      if (!(pdf > 0.0)) return ShiftStatus::zero_contribution;
      set_scatter(ov, b, wo_l, dir, f, pdf);
      return ShiftStatus::ok;
    }
    // The same Dirac lobe (its value and probability depend on wi only); its direction
    // must be the walked one up to float round-off.
    if (!wi_consistent(ov)) return ShiftStatus::zero_contribution;
    const auto bs = pathspace::sample_dirac_lobe(*ov.hit.bsdf, ctx, ov.wi, b.lobe, b.u_lobe);
    if (!bs || !(bs->pdf > 0.0f) || (bs->wo - wo_l).norm() > 1e-3f) return ShiftStatus::zero_contribution;
    set_scatter(ov, b, wo_l, dir, bs->weight * bs->pdf, double(bs->pdf));
    ov.eta = bs->eta;
    return ShiftStatus::ok;
  };
  for (int j = k + 1; j <= m; ++j) {
    const Vec3d target = j < m ? w.chain.v[size_t(m - j)].p() : d3(base[m].p());
    const Vec3 dir = (target.cast<float>() - o[j - 1].p()).normalized();
    const ShiftStatus ss = scatter_to(j - 1, dir);
    if (ss != ShiftStatus::ok) return ss;
    const auto hit = m_scene.trace_from(o[j - 1].hit, dir);
    if (!hit || hit->shape != base[j].hit.shape || !((d3(hit->p) - target).norm() <= tol))
      return ShiftStatus::occluded;
    Vertex nv;
    if (j == m) {
      nv = base[m];  // the offset rejoins the base at c
    } else {
      nv.kind = VertexKind::surface;
      nv.hit = *hit;
      nv.connectable = pathspace::is_connectable(hit->bsdf, m_opt.threshold);
    }
    nv.wi = nv.hit.shading.to_local(-dir);
    nv.emission = pathspace::emitted(m_scene, nv, -dir);
    o.append(nv);
  }
  // Invertibility (the reverse shift must succeed with the same strategy): the reverse
  // shift walks the offset's own float chain back to b; Newton's basin is not symmetric
  // (near caustic folds the walk back fails for ~10% of converged forward walks in the
  // Cornell box), so the forward shift runs that very walk and fails with it. Then
  // T(x) exists iff T^-1(T(x)) does, as the symmetric MIS weights require.
  manifold::Chain back_exact;
  manifold::WalkResult back;
  st = solve(o, k, m, d3(base[k].p()), back_exact, back, ws);
  out.walk_traces = ws.traces;
  // ... and must find the base's own chain, not another solution with the same ends.
  const double back_tol = m_walk.reverse_tolerance * std::max(1e-3, double(m_scene.scene_radius()));
  for (int i = 1; st == WalkStatus::ok && i < exact.n(); ++i)
    if (!((back.chain.v[size_t(i)].p() - exact.v[size_t(i)].p()).norm() <= back_tol)) st = WalkStatus::not_reversible;
  if (st != WalkStatus::ok) {
    out.walk_status = int(WalkStatus::not_reversible);
    return ShiftStatus::not_invertible;
  }
  if (m_walk_as_fallback) {
    // The reverse shift walks only if its own copy (the offset's direction at b' copied
    // to b) does not stay on the chain's shapes.
    thread_local ShiftResult back_copy;
    back_copy.reset(o.size());
    back_copy.path.raster = base.raster;
    for (int j = 0; j <= k; ++j) back_copy.path.append(base[j]);
    if (copy_chain(o, k, m, back_copy) && same_shapes(o, back_copy, k, m)) {
      out.walk_status = int(WalkStatus::not_reversible);
      out.walk_refused = true;
      return ShiftStatus::not_invertible;
    }
  }
  out.jacobian[size_t(k)] = reported_manifold_jacobian(J, m_opt.fault);
  out.reconnected = m;
  return ShiftStatus::ok;
}

}  // namespace dp::gradients
