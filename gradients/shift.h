// Shift mappings T_ij: a base path x sampled in pixel i -> an offset path T(x) in pixel j
// with the Jacobian |dT/dx| (Lehtinen et al. 2013, Sec. 4; Kettunen et al. 2015, Sec. 5).
// A walk (pathspace/path.h) stands for a family of concrete paths (one NEE path and one
// BSDF path per vertex); a shift maps all of them at once, vertex by vertex, so a
// ShiftResult holds per-vertex facts:
//  * path: the offset walk. Vertices [0, alive) exist; vertex k carries the offset's own
//    scattering values (f_cos, pdf: what pixel j's walk would use) and the base's Russian
//    roulette probability (RR follows the base, Kettunen 2015, Sec. 5.3).
//  * jacobian[k]: factor of the direction leaving x_k (jacobians.h); the Jacobian of
//    the prefix x_0..x_k is prefix_jacobian(k) = prod_{m<k} jacobian[m].
//  * nee_status[k], nee_jacobian[k]: the shifted NEE path of vertex k (path.nee[k]).
//  * status: ok if every base vertex was shifted, else why vertex `alive` failed.
// Failure causes: not_invertible (the reverse shift would use another strategy, or a
// strategy is undefined: delta vs smooth lobe, index-matched refraction), occluded (a
// reconnection segment is blocked), miss (base and offset disagree on hitting the
// scene), zero_contribution (the offset cannot be sampled by pixel j's walk: zero pdf,
// shading-normal inconsistency, missing Dirac lobe). Every Jacobian is in double.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pathspace/path.h"

namespace dp::gradients {

enum class ShiftStatus : uint8_t { ok, not_invertible, occluded, miss, zero_contribution };
constexpr int kShiftStatusCount = 5;
const char* to_string(ShiftStatus s);

// How one direction of the offset was produced (for statistics and tests).
// manifold: a segment of a specular chain re-solved by a manifold walk (manifold_shift.h).
enum class StepKind : uint8_t {
  none, primary, reconnect, half_vector, dirac, copy, nee_reconnect, nee_half_vector, nee_copy, manifold
};
constexpr int kStepKindCount = 10;
const char* to_string(StepKind k);

// A deliberate defect of the Jacobians a shift reports, for the tests' negative
// controls only (tests/integrators/test_gpt_unbiased.cpp, test_gpt_glossy.cpp: G-PT run
// with it must be rejected as biased). Carried explicitly (ReconnectionShiftOptions::fault,
// set from GptSettings::faults by C++ test code); no scene key or --set reaches it.
enum class JacobianFault : uint8_t {
  none,
  unit,              // every factor |dT/dx| reported as 1 (reconnection, half vector, manifold; path and NEE)
  unit_half_vector,  // only the half-vector copies' factors (glossy/specular vertices; path and NEE)
  unit_manifold,     // only the manifold walks' factors (specular chains; G-PT and G-BDPT)
};

// The factor a shift stores: J itself, or 1 where `fault` forces it (`half_vector`: J is
// a half-vector copy's factor). One predictable branch when there is no fault.
inline double reported_jacobian(double J, JacobianFault fault, bool half_vector) {
  if (fault == JacobianFault::none) [[likely]]
    return J;
  return fault == JacobianFault::unit || (fault == JacobianFault::unit_half_vector && half_vector) ? 1.0 : J;
}
// The same for a manifold walk's factor.
inline double reported_manifold_jacobian(double J, JacobianFault fault) {
  if (fault == JacobianFault::none) [[likely]]
    return J;
  return fault == JacobianFault::unit || fault == JacobianFault::unit_manifold ? 1.0 : J;
}

struct ShiftResult {
  pathspace::Path path;
  std::vector<double> jacobian;
  std::vector<StepKind> step;  // step[k]: how the direction leaving x'_k was made
  std::vector<ShiftStatus> nee_status;
  std::vector<double> nee_jacobian;
  std::vector<StepKind> nee_step;
  ShiftStatus status = ShiftStatus::ok;
  int alive = 0;
  int reconnected = -1;  // index of the base vertex the offset rejoined, -1 if none
  // The manifold walk of this shift, if any (at most one: the offset rejoins the base at
  // the chain's end): status (manifold::WalkStatus as an integer, -1 = no walk),
  // iterations and chain re-traces, for the integrator's manifold statistics.
  int walk_status = -1;
  // With walk_status set: the walk converged but was refused because the walked
  // offset's own half-vector copy stays on the chain (the reverse shift would copy).
  bool walk_refused = false;
  int walk_iterations = 0;
  int64_t walk_traces = 0;
  // Vertices declared specular by the incremental manifold walk (incremental_shift.h; 0:
  // none, the offset reconnected as the hybrid shift does).
  int declared = 0;
  // The shift failed because an offset vertex's class differed from its base vertex's
  // (ReconnectionShiftOptions::match_classes; status not_invertible).
  bool class_mismatch = false;

  void reset(int n);
  bool vertex_ok(int k) const { return k < alive; }
  bool nee_ok(int k) const { return k < alive && nee_status[size_t(k)] == ShiftStatus::ok; }
  double prefix_jacobian(int k) const;
  double total_jacobian() const { return prefix_jacobian(alive - 1); }
};

class Shift {
 public:
  virtual ~Shift() = default;
  // Shifts `base` (built by pathspace::PathBuilder) by `raster_offset` pixels (e.g. (1,0)
  // for the right neighbour). `out` is overwritten (its capacity is reused).
  virtual void shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const = 0;
  virtual std::string name() const = 0;
};

// T_0 of Manzi et al. 2014 (Sec. 3.3): the offset is the base path itself (Jacobian 1);
// only the pixel it is credited to changes, so its value comes from the pixel filter.
class IdentityShift final : public Shift {
 public:
  void shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const override;
  std::string name() const override { return "identity"; }
};

}  // namespace dp::gradients
