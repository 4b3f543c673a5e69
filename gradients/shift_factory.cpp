#include "gradients/shift_factory.h"

#include "core/error.h"
#include "gradients/manifold_shift.h"
#include "gradients/reconnection_shift.h"

namespace dp::gradients {

std::unique_ptr<Shift> make_shift(const scene::Scene& scene, const ShiftChoice& c) {
  const ReconnectionShiftOptions ro{c.threshold, scene.caps().has_glossy || scene.caps().has_specular, c.fault,
                                    c.match_classes};
  std::shared_ptr<const IncrementalManifoldShift> inc;
  if (c.incremental && c.kind != "identity") {
    IncrementalShiftOptions io;
    io.reconnection = ro;
    io.max_declared = c.incremental_max_declared;
    inc = std::make_shared<IncrementalManifoldShift>(scene, io, c.incremental);
  }
  if (c.kind == "reconnection") {
    if (inc) return std::make_unique<IncrementalManifoldShift>(scene, IncrementalShiftOptions{ro, {}, c.incremental_max_declared, true}, c.incremental);
    return std::make_unique<ReconnectionShift>(scene, ro);
  }
  if (c.kind == "manifold")
    return std::make_unique<ManifoldShift>(
        scene, ManifoldShiftOptions{ro, {}, c.manifold_emitter_chains_only, c.manifold_walk_as_fallback, inc});
  if (c.kind == "identity") return std::make_unique<IdentityShift>();
  throw ValueError("unknown shift '" + c.kind + "' (reconnection | manifold | identity)", "--set");
}

}  // namespace dp::gradients
