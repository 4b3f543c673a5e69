#include "integrators/gpr/gpr_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "gradients/gradient_buffers.h"
#include "integrators/gpr/gpr_tracer.h"
#include "integrators/gradient_passes.h"
#include "integrators/pr/reuse_iterations.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

RenderResult GprIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  const GprTracer tracer(scene, m_settings, options.max_depth);
  GradientPasses passes;
  // One buffer for all threads: the inner parts of one iteration's tiles are disjoint and
  // a tile writes only its inner pixels and the pairs starting there (gpr_tracer.h).
  passes.total = gradients::GradientBuffers(w, h);
  core::Timer timer;
  const ReuseSchedule sched = run_reuse_iterations(
      w, h, m_settings.reuse.tile, options, "gpr",
      [&](const ReuseTile& tile, core::Rng& rng, int thread) {
        GprCounters counters;
        tracer.render_tile(tile, rng, passes.total, counters);
        counters.flush(thread_stats[size_t(thread)]);
      },
      m_settings.jitter);
  passes.passes = passes.kept = sched.iterations;
  passes.partial = sched.partial;
  passes.render_seconds = sched.seconds;

  RenderResult result =
      options.raw ? gradient_raw_result(passes, thread_stats)
                  : gradient_result(passes, thread_stats, m_settings.alpha, m_settings.reconstruction, options, m_json);
  // The paper's Table 1: base paths skipped by Russian roulette, and base paths reused per
  // pixel and per gradient estimate (also as a share of the extended tile's base paths).
  const core::Stats& st = result.stats;
  const double bases = double(std::max<int64_t>(1, st.get("gpr.rr.bases")));
  const double per_tile = bases / double(std::max<int64_t>(1, st.get("gpr.tiles")));
  const double ppp = double(st.get("gpr.table1.pixel_paths")) /
                     double(std::max<int64_t>(1, st.get("gpr.table1.pixel_estimates")));
  const double ppg = double(st.get("gpr.table1.gradient_paths")) /
                     double(std::max<int64_t>(1, st.get("gpr.table1.gradient_estimates")));
  result.info["iterations"] = sched.iterations;
  result.info["rr_skipped_percent"] = 100.0 * double(st.get("gpr.rr.skipped")) / bases;
  result.info["bases_per_tile"] = per_tile;
  result.info["paths_per_pixel"] = ppp;
  result.info["paths_per_gradient"] = ppg;
  result.info["paths_per_pixel_percent"] = 100.0 * ppp / per_tile;
  result.info["paths_per_gradient_percent"] = 100.0 * ppg / per_tile;
  result.wall_seconds = timer.seconds();
  return result;
}

// The reconstruction of (summed) raw buffers, as gpt's: the same code a single render runs.
RenderResult GprIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
