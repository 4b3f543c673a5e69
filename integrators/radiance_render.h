// Scheduling shared by the integrators that estimate one radiance value per camera ray
// (`path`, `volpath`): tiles and passes (tile_scheduler.h), the raw buffers of
// `--partial` (the sum "radiance" and the count "spp"), and finish(), which divides them
// per pixel. The integrator supplies the per-tile work.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "integrators/bdpt/splat_merger.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

// Renders `spp` samples for every pixel of the tile into sum[y * width + x], counting
// into `stats` (the calling thread's own).
using RadianceTileFunction =
    std::function<void(const Tile& tile, int spp, core::Rng& rng, std::vector<Rgbd>& sum, core::Stats& stats)>;

RenderResult render_radiance(const scene::Scene& scene, const RenderOptions& options, const std::string& label,
                             const RadianceTileFunction& fn);
// The same with light tracing: the tile function also appends splats (pixel, value) for
// its light paths, one per camera sample, in units where the image adds sum(values) *
// pixel count / light paths (pathspace/bidir_connect.h, t = 1). They are merged in a fixed
// order (bdpt/splat_merger.h: bit-identical for any thread count) into the raw sum "light".
using RadianceSplatTileFunction = std::function<void(const Tile& tile, int spp, core::Rng& rng, std::vector<Rgbd>& sum,
                                                     std::vector<Splat>& splats, core::Stats& stats)>;
RenderResult render_radiance_with_splats(const scene::Scene& scene, const RenderOptions& options,
                                         const std::string& label, const RadianceSplatTileFunction& fn);
// The final image (and an "spp" layer where pixels lack samples) from raw buffers; a sum
// "light" (render_radiance_with_splats) is added scaled by pixel count / camera samples.
RenderResult finish_radiance(const core::RawImage& raw, const RenderOptions& options);

}  // namespace dp::integrators
