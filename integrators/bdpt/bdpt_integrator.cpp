#include "integrators/bdpt/bdpt_integrator.h"

#include "integrators/bdpt/bdpt_tracer.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

RenderResult BdptIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero()), splat_sum(size_t(w) * size_t(h), Rgbd::Zero());
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  std::vector<BdptScratch> scratch(static_cast<size_t>(threads));
  const BdptTracer tracer(scene, m_settings, options.max_depth);
  const int tiles = ((w + kTileSize - 1) / kTileSize) * ((h + kTileSize - 1) / kTileSize);
  SplatMerger merger(size_t(tiles), splat_sum);

  const ScheduleResult sched = run_tiles(
      w, h, options, "bdpt",
      [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
        core::Stats& stats = thread_stats[size_t(thread)];
        BdptScratch& sc = scratch[size_t(thread)];
        BdptCounters counters;
        std::vector<Splat> splats;
        // A sample with a non-finite value is dropped whole (radiance and splats), counted.
        const int64_t dropped = accumulate_tile(tile, spp, rng, w, sum, [&](const Vec2& raster, Rgb& L) {
          return tracer.sample(raster, rng, sc, L, splats, counters);
        });
        merger.submit(tile.index, std::move(splats));
        counters.flush(stats);
        stats.add("bdpt.paths", int64_t(spp) * (tile.x1 - tile.x0) * (tile.y1 - tile.y0));
        stats.add("bdpt.nan_dropped", dropped);
      },
      [&](int64_t, bool) { merger.finish_pass(); });

  // Light paths traced = camera samples taken (one light subpath per camera sample).
  double light_paths = 0;
  for (size_t i = 0; i < sched.tiles.size(); ++i) {
    const Tile& t = sched.tiles[i];
    light_paths += double(sched.tile_spp[i]) * double((t.x1 - t.x0) * (t.y1 - t.y0));
  }
  const double splat_scale = light_paths > 0 ? double(w) * double(h) / light_paths : 0.0;
  RenderResult result;
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const int64_t n = sched.spp_at(x, y);
      Rgbd v = splat_sum[i] * splat_scale;
      if (n > 0) v += sum[i] / double(n);
      img(x, y) = v.cast<float>();
    }
  result.layers.push_back({"", std::move(img)});
  for (const auto& s : thread_stats) result.stats.merge(s);
  sched.fill(result);
  result.info["light_paths"] = light_paths;
  return result;
}

}  // namespace dp::integrators
