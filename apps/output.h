// Writing a render's outputs: FILE.exr (every layer), FILE.png (sRGB preview of the
// first layer) and FILE.json (the caller's sidecar fields + timings, counters, spp).
#pragma once

#include <string>

#include "core/json.h"
#include "integrators/integrator.h"

namespace dp::apps {

// Replaces the extension of `exr_path` (".exr" or none) by `ext` (".png", ".json").
std::string sibling_path(const std::string& exr_path, const std::string& ext);
void write_render_outputs(const std::string& exr_path, integrators::RenderResult& result, core::Json sidecar);
// FILE.json alone: the caller's fields + wall time, spp range, partial, peak memory,
// counters, info, and the layer names and mean of the first layer if there are layers.
void write_sidecar(const std::string& exr_path, const integrators::RenderResult& result, core::Json sidecar);

}  // namespace dp::apps
