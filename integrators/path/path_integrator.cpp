#include "integrators/path/path_integrator.h"

#include "integrators/path/path_tracer.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

RenderResult PathIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero());
  std::vector<core::Stats> thread_stats(size_t(resolve_threads(options)));
  const PathTracer tracer(scene, m_settings, options.max_depth);

  const ScheduleResult sched = run_tiles(w, h, options, "path", [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
    core::Stats& stats = thread_stats[size_t(thread)];
    PathCounters counters;
    const int64_t dropped = accumulate_tile(tile, spp, rng, w, sum, [&](const Vec2& raster, Rgb& L) {
      L = tracer.radiance(cam.generate_ray(raster), rng, counters);
      return is_finite(L);  // a non-finite sample is counted and dropped, never splatted
    });
    counters.flush(stats);
    stats.add("pt.paths", int64_t(spp) * (tile.x1 - tile.x0) * (tile.y1 - tile.y0));
    stats.add("pt.nan_dropped", dropped);
  });

  RenderResult result;
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int64_t n = sched.spp_at(x, y);
      if (n > 0) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] / double(n)).cast<float>();
    }
  result.layers.push_back({"", std::move(img)});
  for (const auto& s : thread_stats) result.stats.merge(s);
  sched.fill(result);
  return result;
}

}  // namespace dp::integrators
