// The manifold shift: the G-PT hybrid shift (reconnection_shift.h) extended by a
// manifold walk through specular chains (Jakob & Marschner 2012; used as the shift of
// G-BDPT, Manzi et al. 2015, Sec. 4; ALGORITHMS.md "G-BDPT" and "Manifold walks").
//
// Where the hybrid shift would copy the half vector at a connectable vertex b = x_k
// whose next vertex is specular (a caustic chain: the offset then drifts through the
// chain and rarely reaches the same light), this shift keeps the end of the chain:
//   x_k = b (connectable), x_{k+1} .. x_{m-1} specular, x_m = c (connectable surface),
// the offset's b' = x'_k already made by the prefix rules; the chain pinned at c with its
// end moved from b to b' is walked (manifold::walk, ideal specular constraints), giving
// x'_{k+1} .. x'_{m-1}, and the offset rejoins the base at c (afterwards it shares every
// base vertex, as after a reconnection).
//
// Jacobian (parameterization of jacobians.h: the solid angle of the direction sampled at
// b; delta lobes sample no direction). The chain maps the sampled direction at b to the
// area at c: d w_b = G(b <-> c) / |cos theta_b| dA_c, G the generalized geometry term
// (J&M 2012, Sec. 4.3; projected solid angle at b per unit area at c, symmetric). The
// offset reaches the same c, so
//   |d w'_b' / d w_b| = [G(b' <-> c) / |cos theta'_b'|] / [G(b <-> c) / |cos theta_b|],
// cosines w.r.t. the geometric normals at b and b' (Manzi et al. 2015, Sec. 4, the ratio
// of generalized geometry terms; for ideal specular chains no half-vector determinant
// enters because the chain samples no direction of its own).
//
// When the walk is used (the strategy must be the one the reverse shift picks, so every
// condition is symmetric between base and offset): k >= 1, not yet reconnected; b and b'
// connectable, on the same shape, the base sampled a non-delta lobe at b; every chain
// vertex has a purely specular BSDF (only Dirac lobes: no NEE and no BSDF-sampled
// direction of its own), emits nothing, and is not an index-matched refraction; the
// chain ends at a connectable surface vertex c inside the walk (by default only if c is
// an emitter: ManifoldShiftOptions::emitter_chains_only). Then no concrete path of
// the walk ends strictly inside the chain with a nonzero contribution, so shifting the
// whole chain at once is a well-defined map of every contributing path. Otherwise the
// step is exactly ReconnectionShift's (glossy vertices in a chain, chains escaping to the
// environment or cut off by the walk's length keep the half-vector copy).
//
// Strategy (each rule depends only on facts the reverse shift sees the same way, so
// T^-1(T(x)) = x): at a chain start k (b, b' connectable, x_{k+1} not, not reconnected)
// let m be the base's next connectable vertex and C the reconnection shift's half-vector
// copy of x'_{k+1} .. x'_m; "C stays" if it succeeds and lands on the base's shapes.
//  * eligible chain, walk_as_fallback: C where C stays; else the walk, accepted only if
//    the copy of the walked offset back to b does not stay (else the reverse shift would
//    copy, not walk). The copy keeps the direction at b, so the pair's ratio is ~1 where
//    the offset still reaches the light; the walk keeps the light point c, whose ratio
//    G(b'<->c)/G(b<->c) is the caustic of a point light and spreads near its folds
//    (bench/RESULTS.md): the walk replaces only copies that miss.
//  * eligible chain, !walk_as_fallback: the walk.
//  * chain not eligible: C, except that if C's own chain is eligible (the copy drifted
//    onto an emitter) the reverse shift would walk: not_invertible.
//
// Failures: the walk's failure (manifold::WalkStatus, counted by cause in the result)
// maps to `occluded` for miss / different_object, else `not_invertible` (no offset chain
// found); a float re-trace of the walked chain from b' that hits another surface is
// `occluded`; a Dirac lobe the offset cannot produce is `zero_contribution`. The reverse
// walk (the offset's own chain walked back to b, exactly as the reverse shift does it)
// must converge too, else `not_invertible` (walk status not_reversible): Newton's basin
// is not symmetric near caustic folds, and a shift that exists in one direction only
// would bias the symmetric MIS.
#pragma once

#include <memory>

#include "gradients/incremental_shift.h"
#include "gradients/reconnection_shift.h"
#include "manifold/walk.h"

namespace dp::gradients {

struct ManifoldShiftOptions {
  ReconnectionShiftOptions reconnection;
  manifold::WalkSettings walk;  // 20 iterations, 1e-7 (check_reversible: --paranoid / tests)
  // Walk only chains whose end c is an emitter (the caustic paths L S+ D.. where the
  // half-vector copy drifts off the light). Chains ending on other connectable surfaces
  // keep the half-vector copy: there it is as good (the offset rejoins the base one
  // vertex later) and a walk costs ~14 chain re-traces (forward + reverse), measured on
  // cornell_specular.yaml (bench_gpt --diagnose, bench/RESULTS.md). A per-shape
  // property, so the choice stays symmetric.
  bool emitter_chains_only = true;
  // Walk a chain only where the half-vector copy of the whole chain does not stay on the
  // base's shapes (false: walk every eligible chain). See "Strategy" above.
  bool walk_as_fallback = true;
  // Optional INCMW (Manzi et al. 2014, Sec. 3.4; incremental_shift.h): where this shift
  // would reconnect at x_{k+1} and `incremental` declares x_{k+1} specular, its
  // incremental walk makes the step instead. Null: Lehtinen 2013's T_1 alone. The two
  // strategies never compete for a vertex: a specular-chain start has x_{k+1} not
  // connectable, INCMW needs it connectable.
  std::shared_ptr<const IncrementalManifoldShift> incremental;
};

class ManifoldShift final : public ReconnectionShift {
 public:
  ManifoldShift(const scene::Scene& scene, const ManifoldShiftOptions& options)
      : ReconnectionShift(scene, options.reconnection),
        m_walk(options.walk),
        m_emitter_chains_only(options.emitter_chains_only),
        m_walk_as_fallback(options.walk_as_fallback),
        m_incremental(options.incremental) {}
  void shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const override;
  std::string name() const override { return m_incremental ? "manifold+incmw" : "manifold"; }
  const manifold::WalkSettings& walk_settings() const { return m_walk; }

  // Index m of the chain's end c if the walk strategy applies at base vertex k (offset
  // prefix x'_0..x'_k in out.path), else -1.
  int chain_end(const pathspace::Path& base, int k, const ShiftResult& out) const;
  // The same test with offset vertex x'_k = ob (not yet reconnected).
  int chain_end(const pathspace::Path& base, int k, const pathspace::Vertex& ob) const;
  // The chain x_m (pinned), x_{m-1} .. x_{k+1}, x_k (end) of a base path, in double;
  // nullopt if a vertex has no valid local frame.
  std::optional<manifold::Chain> make_chain(const pathspace::Path& base, int k, int m) const;

 protected:
  ShiftStatus step(const pathspace::Path& base, int k, ShiftResult& out) const override;

 private:
  ShiftStatus walk_chain(const pathspace::Path& base, int k, int m, ShiftResult& out) const;
  // The reconnection shift's steps k .. m-1 (the half-vector copy through the chain) into
  // r, whose offset prefix ends at x'_k; true iff every step succeeded.
  bool copy_chain(const pathspace::Path& base, int k, int m, ShiftResult& r) const;
  // The copy reached x'_m and x'_{k+1} .. x'_m lie on the base's shapes (connectable
  // exactly where the base is): the reverse shift's copy retraces the same structure.
  static bool same_shapes(const pathspace::Path& base, const ShiftResult& r, int k, int m);
  // Would the reverse shift of `offset` (a copy whose chain does not stay on base's
  // shapes), with offset prefix base[0..k], walk its chain successfully?
  bool reverse_walks(const pathspace::Path& offset, int k, const pathspace::Path& base) const;
  // Re-traces the chain x_k .. x_m of `path` in double from x_k and walks its end to
  // `target` (c pinned): `exact` is the re-traced chain, `w` the walk.
  manifold::WalkStatus solve(const pathspace::Path& path, int k, int m, const Vec3d& target, manifold::Chain& exact,
                             manifold::WalkResult& w, manifold::WalkStats& ws) const;
  manifold::WalkSettings m_walk;
  bool m_emitter_chains_only;
  bool m_walk_as_fallback;
  std::shared_ptr<const IncrementalManifoldShift> m_incremental;
};

// The shift failure a walk failure maps to: miss / different_object -> occluded, other
// failures -> not_invertible (no offset chain found).
ShiftStatus shift_status(manifold::WalkStatus s);

// |d w'_b' / d w_b| of two chains pinned at the same c (see header): `base` ends at b,
// `offset` at b'. ok, or the status of a degenerate chain (then J is not set).
manifold::WalkStatus manifold_shift_jacobian(const manifold::Chain& base, const manifold::Chain& offset, double& J);

}  // namespace dp::gradients
