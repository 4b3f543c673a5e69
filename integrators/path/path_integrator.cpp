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
    int64_t dropped = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        Rgbd acc = Rgbd::Zero();
        for (int s = 0; s < spp; ++s) {
          const Vec2 raster(float(x) + rng.uniform(), float(y) + rng.uniform());
          const Rgb L = tracer.radiance(cam.generate_ray(raster), rng, counters);
          if (!is_finite(L)) {
            ++dropped;  // counted and dropped, never splatted
            continue;
          }
          acc += L.cast<double>();
        }
        sum[size_t(y) * size_t(w) + size_t(x)] += acc;
      }
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
  result.wall_seconds = sched.seconds;
  result.min_spp = sched.min_spp();
  result.max_spp = sched.max_spp();
  result.partial = sched.partial;
  result.info["passes"] = sched.passes;
  return result;
}

}  // namespace dp::integrators
