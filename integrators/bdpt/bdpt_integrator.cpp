#include "integrators/bdpt/bdpt_integrator.h"

#include <algorithm>

#include "integrators/bdpt/bdpt_tracer.h"
#include "integrators/raw_result.h"
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
        std::vector<Splat> splats;
        // A sample with a non-finite value is dropped whole (radiance and splats), counted.
        trace_tile<BdptCounters>(tile, spp, rng, w, sum, stats, "bdpt",
                                 [&](const Vec2& raster, Rgb& L, BdptCounters& counters) {
                                   return tracer.sample(raster, rng, sc, L, splats, counters);
                                 });
        merger.submit(tile.index, std::move(splats));
      },
      [&](int64_t, bool) { merger.finish_pass(); });

  core::RawImage raw;
  raw.width = w;
  raw.height = h;
  raw.sums["camera"] = std::move(sum);
  raw.sums["light"] = std::move(splat_sum);
  raw.counts["spp"] = spp_counts(sched, w, h);
  RenderResult result = finish_tiled([this](const core::RawImage& r, const RenderOptions& o) { return finish(r, o); },
                                     std::move(raw), sched, options);
  for (const auto& s : thread_stats) result.stats.merge(s);
  return result;
}

RenderResult BdptIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  const std::vector<Rgbd>& sum = raw.sum("camera");
  const std::vector<Rgbd>& splat_sum = raw.sum("light");
  const std::vector<int64_t>& count = raw.count("spp");
  // Light paths traced = camera samples taken (one light subpath per camera sample); the
  // light-tracing splats are divided by their number per pixel of the image.
  double light_paths = 0;
  for (const int64_t n : count) light_paths += double(n);
  const double splat_scale = light_paths > 0 ? double(raw.pixels()) / light_paths : 0.0;
  RenderResult result;
  core::Image img(raw.width, raw.height);
  for (size_t i = 0; i < count.size(); ++i) {
    Rgbd v = splat_sum[i] * splat_scale;
    if (count[i] > 0) v += sum[i] / double(count[i]);
    img[i] = v.cast<float>();
  }
  result.layers.push_back({"", std::move(img)});
  fill_counts(count, raw.width, raw.height, options, result);
  result.info["light_paths"] = light_paths;
  return result;
}

}  // namespace dp::integrators
