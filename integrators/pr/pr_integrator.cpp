#include "integrators/pr/pr_integrator.h"

#include <algorithm>
#include <atomic>

#include "core/progress.h"
#include "core/rng.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/pr/pr_tracer.h"
#include "integrators/pr/reuse_tiling.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

RenderResult PrIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero());
  std::vector<int64_t> count(size_t(w) * size_t(h), 0);
  const PrTracer tracer(scene, m_settings, options.max_depth);
  const bool timed = options.time_budget > 0;
  const int spp = std::max(1, options.spp);

  core::Timer timer;
  core::Progress progress("pr", timed ? 1000 : spp, options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  int64_t iterations = 0;
  for (int64_t it = 0; timed || it < spp; ++it) {
    const bool first = it == 0;  // always completes: every pixel gets a sample
    if (!first && should_stop()) break;
    const ReuseTiling tiling = jittered_tiling(w, h, m_settings.tile, options.seed, it);
    core::parallel_for(
        int64_t(tiling.tiles.size()), threads,
        [&](int64_t item, int thread) {
          if (!first && should_stop()) {
            stop.store(true);
            return;
          }
          const ReuseTile& tile = tiling.tiles[size_t(item)];
          core::Rng rng(options.seed, core::mix64(uint64_t(it) * 0x9e3779b97f4a7c15ull + uint64_t(item)));
          PrCounters counters;
          tracer.render_tile(tile, rng, w, sum, counters);  // tiles are disjoint: no two workers share a pixel
          counters.flush(thread_stats[size_t(thread)]);
          for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) ++count[size_t(y) * size_t(w) + size_t(x)];
        },
        &stop);
    ++iterations;
    if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
    else progress.advance(1);
    if (stop.load()) break;
  }
  progress.finish();

  RenderResult result;
  core::Image img(w, h), counts(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (count[i] > 0) img(x, y) = (sum[i] / double(count[i])).cast<float>();
      counts(x, y) = Rgb::Constant(float(count[i]));
    }
  result.layers.push_back({"", std::move(img)});
  for (const auto& s : thread_stats) result.stats.merge(s);
  const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
  result.min_spp = count.empty() ? 0 : *lo;
  result.max_spp = count.empty() ? 0 : *hi;
  result.partial = (options.stop && options.stop->load()) || (!timed && result.min_spp < spp);
  if (result.partial || result.min_spp != result.max_spp) result.layers.push_back({"spp", std::move(counts)});
  // Table 1 of the paper: base paths that reach a pixel's estimate, per pixel and iteration.
  const int64_t pixel_iterations = std::max<int64_t>(1, result.stats.get("pr.base_paths"));
  result.info["iterations"] = iterations;
  result.info["paths_per_pixel"] =
      double(result.stats.get("pr.estimates.own") + result.stats.get("pr.estimates.reused")) / double(pixel_iterations);
  result.info["settings"] = m_json;
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace dp::integrators
