#include "integrators/gbdpt/gbdpt_integrator.h"

#include "core/timer.h"
#include "integrators/gbdpt/gbdpt_tracer.h"
#include "integrators/gradient_passes.h"

namespace dp::integrators {

RenderResult GbdptIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  std::vector<GbdptScratch> scratch(static_cast<size_t>(threads));
  const GbdptTracer tracer(scene, m_settings, options.max_depth);
  core::Timer timer;
  const GradientPasses passes = render_gradient_passes(
      w, h, options, "gbdpt",
      [&](const Tile& tile, int spp, core::Rng& rng, int thread, gradients::GradientBuffers& buf) {
        GbdptCounters counters;
        GbdptScratch& sc = scratch[size_t(thread)];
        for (int y = tile.y0; y < tile.y1; ++y)
          for (int x = tile.x0; x < tile.x1; ++x)
            for (int s = 0; s < spp; ++s) tracer.sample(x, y, rng, sc, buf, counters);
        counters.flush(thread_stats[size_t(thread)]);
      });

  RenderResult result = options.raw ? gradient_raw_result(passes, thread_stats)
                                    : gradient_result(passes, thread_stats, m_settings.alpha,
                                                      m_settings.reconstruction, options, m_json);
  result.wall_seconds = timer.seconds();
  return result;
}

RenderResult GbdptIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
