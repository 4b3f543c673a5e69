// A path-space chain's state as JSON, for `--set replay=CHAIN:STEP` (integrators/mlt):
// one chain re-run to a step and written out, so that a firefly or a rejected proposal
// can be studied alone. Numbers carry the JSON writer's 9 significant digits; two replays
// of the same seed and chain write the same text.
#pragma once

#include "core/json.h"
#include "mcmc/path_state.h"

namespace dp::mcmc {

// vertices (kind, position, geometric normal, Dirac flag and lobe, shape/primitive, emitter),
// raster, c_ref and lum, ref, inv_c (1 / lum C_s per strategy s).
core::Json path_state_json(const PathState& s);

}  // namespace dp::mcmc
