// The incremental manifold walk shift (INCMW) of Manzi et al. 2014, Sec. 3.4 ("Canceling
// Geometry Terms", "Incremental Approach") on top of the G-PT hybrid shift
// (reconnection_shift.h).
//
// Strategy. Up to the first vertex b = x_k where the hybrid shift would RECONNECT to
// x_{k+1} (k >= 1, not yet reconnected; x_k, x'_k, x_{k+1} connectable, the base sampled a
// non-delta lobe at x_k, x_{k+1} a surface), every step is ReconnectionShift's. There, with
// y_i = x_{k+i}: for i = 1, 2, ... the vertex y_i is DECLARED specular iff
//   i <= max_declared, y_i is declarable (a surface with a connectable BSDF and no emitter:
//   properties of its shape, which the walk preserves), and decide(y_{i-1}, y~_{i-1});
// the decision sees only the previous base and offset vertices, never y_i (Manzi 2014,
// Sec. 3.4, Fig. 6: a rule looking at y_i leaves gaps in the image of the map). A declared
// y_i is moved by manifold::incremental_walk (walk on (y~_{i-1}, y_i, y_{i+1}) keeping y_i's
// reflection half vector, y_{i+1} pinned); the first vertex not declared, y_r, is where
// the offset reconnects (afterwards it shares every base vertex). r = 1: exactly the
// reconnection shift. A declared vertex that cannot be walked (its base lobe refracts, the
// path ends there or continues to the environment, the walk fails) fails the shift at
// b (not_invertible; a walk leaving the surfaces: occluded).
//
// Why the reverse shift T_ji sees every rule the same way (T_ji(T_ij(x)) = x):
//  * the prefix rules are the hybrid shift's (symmetric, Kettunen 2015, Sec. 5.2);
//  * decide() MUST be symmetric in its arguments (e.g. AO(a) > t && AO(b) > t, see
//    symmetric_threshold): the reverse evaluates it on (y~_{i-1}, y_{i-1});
//  * declarability and max_declared depend on the vertex's shape and index only, and the
//    walk keeps y~_i on y_i's shape;
//  * the walk of one declared vertex is an involution: y~_1 keeps h_1 with y_0 -> y~_0 and
//    the pin y_2 = y~_2 shared, so walking y~_1 back to y_0 recovers y_1.
// With two or more declared vertices Manzi's sequential scheme is NOT an involution: step i
// keeps h(y~_{i-1}, y~_i, y_{i+1}) = h(y_{i-1}, y_i, y_{i+1}) with the BASE pin y_{i+1},
// while the reverse pins y~_{i+1} != y_{i+1}. The forward shift therefore runs the reverse
// incremental walk itself (check_reverse) and fails (not_invertible, walk status
// not_reversible) unless it comes back to the base's vertices with the same r; then the
// pair exists in both directions or in neither, as the symmetric MIS weights require.
// Measured (tests/gradients/test_incremental_shift.cpp, concave.yaml, AO > 0.1, 6000
// paths): max_declared 1: 67 walked offsets, |J J^-1 - 1| <= 3e-5; unlimited: 53, and
// multi-step pairs that pass within the reverse tolerance show |J J^-1 - 1| up to 7e-4.
// Hence max_declared = 1 ("one step INCMW", Manzi 2014, Fig. 5c) is the default.
//
// Concrete paths ending at a declared vertex y_i (its NEE path; a BSDF path ending there
// cannot emit: emitters are not declarable) would, shifted on their own, pin y_i's walk at
// the light point instead of y_{i+1}: another offset vertex than the walk's, which a
// ShiftResult (shared vertices) cannot hold. Their NEE fails (not_invertible); whether y_i
// is declared depends only on the prefix y_0..y_i, so the reverse fails on the same paths.
//
// Jacobian (parameterization of jacobians.h: solid angles of the directions leaving
// y_0..y_{r-1}; the prefix fixes y_0 and y~_0). d w_j = |cos theta_{j+1}| / d_j^2 dA_{j+1}
// (cosine at y_{j+1}, geometric normal), y_r is shared, and the area map of y_1..y_{r-1}
// is incremental_walk's exact |det R| / prod |det b~_i| (manifold/incremental.h):
//   factor[j] = [cos~_{j+1} / d~_j^2] / [cos_{j+1} / d_j^2],  j = 0..r-1,
//   factor[r-1] *= |dy~ / dy| (area).
// For r = 1 this is reconnection_jacobian. The half vectors of the declared vertices are
// those of the half-vector parameterization (Kaplanyan et al. 2014; Jakob & Marschner
// 2012, Sec. 4): G(y~_0 <-> y~_1) cancels against the walk's Jacobian (Manzi 2014, Sec. 3.4).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "gradients/reconnection_shift.h"
#include "manifold/incremental.h"

namespace dp::gradients {

// decide(base_prev, offset_prev): declare the next vertex specular? Must be symmetric.
using OcclusionDecision = std::function<bool(const Vec3& base_prev, const Vec3& offset_prev)>;

// The symmetric decision of Manzi 2014, Sec. 4: coefficient(a) > t AND coefficient(b) > t
// (coefficient < 0: no value, e.g. a point not visible to the camera: not declared).
OcclusionDecision symmetric_threshold(std::function<float(const Vec3&)> coefficient, float threshold);

struct IncrementalShiftOptions {
  ReconnectionShiftOptions reconnection;
  manifold::WalkSettings walk;
  int max_declared = 1;       // see header (0 = no limit)
  bool check_reverse = true;  // run the reverse incremental walk (needed with max_declared != 1)
};

class IncrementalManifoldShift final : public ReconnectionShift {
 public:
  IncrementalManifoldShift(const scene::Scene& scene, const IncrementalShiftOptions& options, OcclusionDecision decide)
      : ReconnectionShift(scene, options.reconnection), m_inc(options), m_decide(std::move(decide)) {}
  void shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const override;
  std::string name() const override { return "incremental_manifold"; }

  // Is base vertex k (surface, shape properties only) a vertex that may be declared?
  bool declarable(const pathspace::Vertex& v) const;
  // Does the strategy examine y_1 = x_{k+1} at base vertex k (offset prefix ends at x'_k)?
  bool applies(const pathspace::Path& base, int k, const ShiftResult& out) const;
  // The incremental step at base vertex k where y_1 is declared; nullopt where it is not
  // (the caller's own step applies: ReconnectionShift's here, ManifoldShift's when it
  // composes INCMW with its specular-chain walks, manifold_shift.h).
  std::optional<ShiftStatus> declared_step(const pathspace::Path& base, int k, ShiftResult& out) const;

 protected:
  ShiftStatus step(const pathspace::Path& base, int k, ShiftResult& out) const override;

 private:
  ShiftStatus walk_vertices(const pathspace::Path& base, int k, ShiftResult& out) const;
  IncrementalShiftOptions m_inc;
  OcclusionDecision m_decide;
};

// NEE paths ending at declared vertices have no representable offset (header): fails
// them in a finished shift (out.declared, out.reconnected).
void drop_declared_nee(ShiftResult& out);

// Per-direction solid-angle factors (header, "Jacobian") of an incremental walk:
// factors[j], j = 0..r-1 (r = result.reconnect). False if a segment is degenerate.
bool incremental_direction_factors(const std::vector<manifold::ChainVertex>& base,
                                   const manifold::IncrementalResult& result, std::vector<double>& factors);

}  // namespace dp::gradients
