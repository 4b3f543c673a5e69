#include "integrators/photon_iterations.h"

#include <algorithm>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/iteration_share.h"

namespace dp::integrators {

PhotonIterations render_photon_iterations(const scene::Scene& scene, const RenderOptions& options,
                                          const std::string& label, const VcmSettings& light_settings,
                                          const std::function<VcmIteration(int64_t)>& iteration,
                                          const BeginIterationFn& begin) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * h;
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const IterationShare share(options);
  const int64_t target = share.target;
  const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;
  const int64_t tiles = int64_t(tiles_x) * tiles_y;

  PhotonIterations out;
  out.passes.total = gradients::GradientBuffers(w, h);
  out.thread_stats.resize(static_cast<size_t>(threads));
  std::vector<gradients::GradientBuffers> buffers(static_cast<size_t>(threads), gradients::GradientBuffers(w, h));
  std::vector<core::Stats> iter_stats(static_cast<size_t>(threads));
  LightPathStore light;
  PhotonGrid grid;
  core::Timer timer;
  core::Progress progress(label, timed ? 1000 : target, options.quiet);
  int64_t done = 0;
  while (timed ? timer.seconds() < options.time_budget : done < target) {
    if (options.stop && options.stop->load()) {
      out.passes.partial = true;
      break;
    }
    const int64_t global = share.global(done);
    const VcmIteration it = iteration(global);
    VcmLightCounters lc;
    if (!trace_light_paths(scene, light_settings, it, pixels, threads, options.stop, light, lc)) {
      out.passes.partial = true;
      break;
    }
    if (light_settings.merges()) light.collect_photons(threads);
    else light.photon_pos.clear();
    grid.build(light.photon_pos, it.radius);
    if (!light.photon_pos.empty()) light.gather_photons(grid.order());
    light.photon_pos = {};  // the grid holds its own copy
    const IterationTileFn tile_fn = begin(it, light, grid);
    for (auto& s : iter_stats) s = core::Stats{};
    std::vector<char> tile_done(size_t(tiles), 0);
    core::parallel_for(
        tiles, threads,
        [&](int64_t ti, int thread) {
          const int x0 = int(ti % tiles_x) * kTileSize, y0 = int(ti / tiles_x) * kTileSize;
          const Tile tile{int(ti), x0, y0, std::min(w, x0 + kTileSize), std::min(h, y0 + kTileSize)};
          core::Rng rng(options.seed, (uint64_t(global) << 32) | 0x80000000ull | uint64_t(ti));
          tile_fn(tile, rng, thread, buffers[size_t(thread)], iter_stats[size_t(thread)]);
          tile_done[size_t(ti)] = 1;
        },
        options.stop);
    const bool complete = std::find(tile_done.begin(), tile_done.end(), 0) == tile_done.end();
    const int64_t photons = int64_t(light.photons.size());
    light.release_photons();  // not held through the next light pass
    grid.release();
    for (size_t t = 0; t < buffers.size(); ++t) {
      if (complete) {
        out.passes.total.merge(buffers[t]);
        out.thread_stats[t].merge(iter_stats[t]);
      }
      buffers[t].clear();
    }
    if (!complete) {  // an interrupted iteration is dropped whole
      out.passes.partial = true;
      break;
    }
    out.light += lc;
    out.photons += photons;
    out.last_radius = it.radius;
    ++done;
    if (timed) progress.set_fraction(std::min(1.0, timer.seconds() / options.time_budget));
    else progress.advance();
  }
  progress.finish();
  out.passes.passes = out.passes.kept = done;
  out.passes.partial = out.passes.partial || (!timed && done < target);
  out.passes.render_seconds = timer.seconds();
  return out;
}

}  // namespace dp::integrators
