#include "integrators/pr/pr_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "integrators/pr/pr_tracer.h"
#include "integrators/pr/reuse_iterations.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

RenderResult PrIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero());
  const PrTracer tracer(scene, m_settings, options.max_depth);
  core::Timer timer;
  const ReuseSchedule sched =
      run_reuse_iterations(w, h, m_settings.tile, options, "pr", [&](const ReuseTile& tile, core::Rng& rng, int thread) {
        PrCounters counters;
        tracer.render_tile(tile, rng, w, sum, counters);
        counters.flush(thread_stats[size_t(thread)]);
      });

  RenderResult result;
  core::Image img(w, h), counts(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (sched.count[i] > 0) img(x, y) = (sum[i] / double(sched.count[i])).cast<float>();
      counts(x, y) = Rgb::Constant(float(sched.count[i]));
    }
  result.layers.push_back({"", std::move(img)});
  for (const auto& s : thread_stats) result.stats.merge(s);
  result.min_spp = sched.min_count();
  result.max_spp = sched.max_count();
  result.partial = sched.interrupted || (options.time_budget <= 0 && result.min_spp < std::max(1, options.spp));
  if (result.partial || result.min_spp != result.max_spp) result.layers.push_back({"spp", std::move(counts)});
  // Table 1 of the paper: base paths that reach a pixel's estimate, per pixel and iteration.
  const int64_t pixel_iterations = std::max<int64_t>(1, result.stats.get("pr.base_paths"));
  result.info["iterations"] = sched.iterations;
  result.info["paths_per_pixel"] =
      double(result.stats.get("pr.estimates.own") + result.stats.get("pr.estimates.reused")) / double(pixel_iterations);
  result.info["settings"] = m_json;
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace dp::integrators
