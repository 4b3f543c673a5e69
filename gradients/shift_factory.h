// One place that builds a Shift from an integrator's settings (G-PT, GD-MLT).
//  kind: "reconnection" (reconnection + half-vector copy, Kettunen et al. 2015),
//        "manifold" (as reconnection, specular chains re-solved by manifold walks where the
//        half-vector copy leaves them; Lehtinen et al. 2013's T_1), "identity" (T_0 of
//        Manzi et al. 2014: the base itself, for tests and ablations).
// The half-vector copy is only enabled when the scene has glossy or specular surfaces
// (nothing to copy otherwise), so such scenes never pay for it.
#pragma once

#include <memory>
#include <string>

#include "gradients/incremental_shift.h"
#include "gradients/shift.h"
#include "scene/scene.h"

namespace dp::gradients {

struct ShiftChoice {
  std::string kind = "reconnection";
  float threshold = 0.05f;                // roughness at or below it is glossy/specular
  bool manifold_emitter_chains_only = true;  // ManifoldShiftOptions::emitter_chains_only
  bool manifold_walk_as_fallback = true;     // ManifoldShiftOptions::walk_as_fallback
  JacobianFault fault = JacobianFault::none;  // tests' negative controls only
  // INCMW (Manzi et al. 2014, Sec. 3.4): when set, "manifold" composes its incremental walk
  // (ManifoldShiftOptions::incremental) and "reconnection" becomes IncrementalManifoldShift.
  // Must be symmetric in its two points (symmetric_threshold).
  OcclusionDecision incremental;
  int incremental_max_declared = 1;  // IncrementalShiftOptions::max_declared
  bool match_classes = false;  // ReconnectionShiftOptions::match_classes (path reusing)
};

// Throws dp::ValueError for an unknown kind.
std::unique_ptr<Shift> make_shift(const scene::Scene& scene, const ShiftChoice& choice);

}  // namespace dp::gradients
