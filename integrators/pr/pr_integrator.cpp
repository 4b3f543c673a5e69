#include "integrators/pr/pr_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "integrators/pr/pr_tracer.h"
#include "integrators/pr/reuse_iterations.h"
#include "integrators/raw_result.h"
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

  core::RawImage raw;
  raw.width = w;
  raw.height = h;
  raw.sums["radiance"] = std::move(sum);
  raw.counts["spp"] = sched.count;
  RenderResult result;
  if (options.raw) {
    result.raw = std::move(raw);
    result.min_spp = sched.min_count();
    result.max_spp = sched.max_count();
  } else {
    RenderOptions target = options;
    if (options.time_budget > 0) target.spp = 0;  // a time budget has no count to fall short of
    result = finish(raw, target);
  }
  result.partial = sched.partial;
  for (const auto& s : thread_stats) result.stats.merge(s);
  // Table 1 of the paper: base paths that reach a pixel's estimate, per pixel and iteration.
  const int64_t pixel_iterations = std::max<int64_t>(1, result.stats.get("pr.base_paths"));
  result.info["iterations"] = sched.iterations;
  result.info["paths_per_pixel"] =
      double(result.stats.get("pr.estimates.own") + result.stats.get("pr.estimates.reused")) / double(pixel_iterations);
  result.info["settings"] = m_json;
  result.wall_seconds = timer.seconds();
  return result;
}

// The image of (summed) raw buffers: sum / iterations per pixel; spp range, partial and the
// "spp" layer where pixels lack iterations (fill_counts).
RenderResult PrIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  const int w = raw.width, h = raw.height;
  const std::vector<Rgbd>& sum = raw.sum("radiance");
  const std::vector<int64_t>& count = raw.count("spp");
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (count[i] > 0) img(x, y) = (sum[i] / double(count[i])).cast<float>();
    }
  RenderResult result;
  result.layers.push_back({"", std::move(img)});
  fill_counts(count, w, h, options, result);
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
