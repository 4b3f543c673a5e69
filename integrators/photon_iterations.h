// Iteration driver of the gradient-domain photon integrators (G-PM `gpm`, G-VCM `gvcm`):
// VCM's iteration (Georgiev et al. 2012; integrators/vcm): one light path per pixel traced
// and stored (vcm_light_pass.h), a photon grid over their mergeable vertices, then the
// image's tiles in parallel, each pixel's camera sample writing into its thread's
// full-image gradients::GradientBuffers (pairs and splats cross tile borders). A complete
// iteration's buffers and counters are merged into the totals; an interrupted one is
// dropped whole, so a partial render is the average of complete iterations. `--spp` =
// iterations; `--time` runs whole iterations until the budget is used. Part k of n
// (RenderOptions::part/parts) runs the global iterations k, k + n, k + 2n, ...
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/stats.h"
#include "integrators/gradient_passes.h"
#include "integrators/tile_scheduler.h"
#include "integrators/vcm/photon_grid.h"
#include "integrators/vcm/vcm_light_pass.h"

namespace dp::integrators {

// Renders one tile of an iteration: every pixel's sample into `buf`, counters into `stats`.
using IterationTileFn =
    std::function<void(const Tile& tile, core::Rng& rng, int thread, gradients::GradientBuffers& buf, core::Stats& stats)>;
// Called once per iteration once its light paths and grid exist; returns the tile renderer.
using BeginIterationFn =
    std::function<IterationTileFn(const VcmIteration& it, const LightPathStore& light, const PhotonGrid& grid)>;

// The usual tile renderer: tracer->sample(x, y, rng, scratch[thread], buf, counters) for
// every pixel, the tile's Counters flushed into the thread's stats.
template <class Counters, class Tracer, class Scratch>
IterationTileFn pixel_tiles(std::shared_ptr<const Tracer> tracer, std::vector<Scratch>& scratch) {
  return [tracer, &scratch](const Tile& tile, core::Rng& rng, int thread, gradients::GradientBuffers& buf,
                            core::Stats& stats) {
    Counters counters;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) tracer->sample(x, y, rng, scratch[size_t(thread)], buf, counters);
    counters.flush(stats);
  };
}

struct PhotonIterations {
  GradientPasses passes;               // passes = kept = complete iterations
  std::vector<core::Stats> thread_stats;  // the complete iterations' counters
  VcmLightCounters light;
  int64_t photons = 0;
  float last_radius = 0;  // the grid radius of the last complete iteration
};

// `iteration(i)`: the settings of iteration i (index, seed, max_depth, radius, mis set by
// the caller); `light_settings` decides what the light pass stores (photons if it merges).
PhotonIterations render_photon_iterations(const scene::Scene& scene, const RenderOptions& options,
                                          const std::string& label, const VcmSettings& light_settings,
                                          const std::function<VcmIteration(int64_t)>& iteration,
                                          const BeginIterationFn& begin);

}  // namespace dp::integrators
