// The G-PT hybrid shift (Kettunen et al. 2015, Sec. 5.2; reference: gpt.cpp of
// mmanzi/gradientdomain-mitsuba, read for understanding only):
//  * primary: the same sub-pixel position in the neighbouring pixel (Jacobian 1);
//  * step k -> k+1 while not yet reconnected:
//      - reconnect to the base vertex x_{k+1} if x_k, x'_k and x_{k+1} are connectable
//        and the base sampled a non-delta lobe at x_k (Jacobian: reconnection_jacobian;
//        a blocked segment fails with `occluded`); afterwards the offset shares every
//        base vertex and direction (factor 1) and only re-evaluates the BSDF at x_{k+1};
//      - else copy a Dirac lobe (same lobe at x'_k, factor 1; a missing lobe fails);
//      - else copy the half vector in the local shading frame, reflection or refraction
//        (jacobians.h), then trace. Invertibility (Kettunen 2015, Sec. 5.2): if the
//        offset could have reconnected at k+1 but the base could not, the reverse shift
//        would pick another strategy, so the shift fails (`not_invertible`);
//      - base and offset must agree on hitting the scene or escaping (`miss`).
//  * NEE at x_k: reconnect to the same light point (area) / direction (infinite) /
//    position (delta light) under the same connectability rule (Jacobian as above,
//    1 for infinite and delta lights); else copy the half vector of the light direction
//    (reflection only) and trace to whatever emitter it reaches. A blocked shadow ray is
//    NOT a failure: the offset NEE path exists with zero contribution and its NEE density
//    still counts in the symmetric MIS weights.
// Vertex classification: pathspace/classify.h with this shift's threshold (it must be
// the threshold the base walk was built with). With `half_vector_enabled` false (scenes
// whose caps have neither glossy nor specular BSDFs) the half-vector machinery is never
// run: a step that would need it fails as not_invertible (it cannot occur when every
// vertex is connectable).
#pragma once

#include "gradients/shift.h"
#include "scene/scene.h"

namespace dp::gradients {

struct ReconnectionShiftOptions {
  float threshold = 0.001f;  // pathspace::kDefaultShiftThreshold
  bool half_vector_enabled = true;
  JacobianFault fault = JacobianFault::none;  // tests' negative controls only (shift.h)
  // Path reusing (Bauszat et al. 2017, Sec. 3.1): every offset vertex traced before the
  // reconnection must have its base vertex's class (connectable or not), else the shift
  // fails as not_invertible (ShiftResult::class_mismatch set). Then every shift of a walk
  // takes the same strategy at every vertex, whichever pixel it starts from, so shifts
  // compose (R_pm(R_qp x) = R_qm x), which the tile-constant MIS weights of Eq. 7 need.
  bool match_classes = false;
};

class ReconnectionShift : public Shift {
 public:
  ReconnectionShift(const scene::Scene& scene, const ReconnectionShiftOptions& options)
      : m_scene(scene), m_opt(options) {}
  void shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const override;
  // Path reusing (Bauszat et al. 2017, Sec. 3.3: a tile's primary rays are traced once):
  // the shift into the pixel of `target`, a walk built at the same sub-pixel position
  // there (correlated primary rays), taking its camera ray and primary vertex instead of
  // re-tracing them. The same offset as shift(base, target.raster - base.raster) (up to the
  // float rounding of that raster difference).
  void shift_to_primary(const pathspace::Path& base, const pathspace::Path& target, ShiftResult& out) const;
  std::string name() const override { return "reconnection"; }
  const ReconnectionShiftOptions& options() const { return m_opt; }

 protected:
  // Makes the direction leaving x'_k and offset vertex x'_{k+1}; returns its status (ok:
  // out.path has k+2 vertices). A derived shift may make several vertices at once (a
  // specular chain, manifold_shift.h): the loop in shift() then skips the steps whose
  // vertex already exists, and still shifts each vertex's NEE sample.
  virtual ShiftStatus step(const pathspace::Path& base, int k, ShiftResult& out) const;
  void shift_nee(const pathspace::Path& base, int k, ShiftResult& out) const;
  ShiftStatus trace_next(const pathspace::Path& base, int k, ShiftResult& out) const;
  // shift() and shift_to_primary(): `target` null = trace the primary ray at `raster`.
  void run(const pathspace::Path& base, const Vec2& raster, const pathspace::Path* target, ShiftResult& out) const;
  // Step 0 from target's primary vertex: the checks of trace_next(base, 0, out).
  ShiftStatus adopt_primary(const pathspace::Path& base, const pathspace::Path& target, ShiftResult& out) const;
  const scene::Scene& m_scene;
  ReconnectionShiftOptions m_opt;
};

}  // namespace dp::gradients
