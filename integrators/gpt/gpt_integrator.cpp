#include "integrators/gpt/gpt_integrator.h"

#include <optional>

#include "core/error.h"
#include "core/rng.h"
#include "core/timer.h"
#include "gradients/gradient_buffers.h"
#include "integrators/gpt/gpt_media_tracer.h"
#include "integrators/gpt/gpt_tracer.h"
#include "integrators/gradient_passes.h"
#include "integrators/tile_scheduler.h"
#include "pathspace/sample_stream.h"

namespace dp::integrators {

RenderResult GptIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  // Scenes with media get the media-aware tracer; without media GptTracer runs unchanged
  // (bit-identical images; its gpt.media_skipped counts the samples).
  const bool media = scene.caps().has_media;
  if (media && m_settings.shift != "reconnection")
    throw ValueError("setting 'shift=" + m_settings.shift + "' of gpt does not render participating media; the "
                     "media tracer shifts by distance copy and reconnection (shift=reconnection)", "--set");
  std::optional<GptTracer> tracer;
  std::optional<GptMediaTracer> media_tracer;
  if (media) media_tracer.emplace(scene, m_settings, options.max_depth);
  else tracer.emplace(scene, m_settings, options.max_depth);
  core::Timer timer;
  const GradientPasses passes = render_gradient_passes(
      w, h, options, "gpt",
      [&](const Tile& tile, int spp, core::Rng& rng, int thread, gradients::GradientBuffers& buf) {
        pathspace::IndependentStream stream(rng);
        if (media) {
          GptMediaCounters counters;
          for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x)
              for (int s = 0; s < spp; ++s) media_tracer->sample(x, y, stream, buf, counters);
          counters.flush(thread_stats[size_t(thread)]);
          return;
        }
        GptCounters counters;
        for (int y = tile.y0; y < tile.y1; ++y)
          for (int x = tile.x0; x < tile.x1; ++x)
            for (int s = 0; s < spp; ++s) tracer->sample(x, y, stream, buf, counters);
        counters.flush(thread_stats[size_t(thread)]);
      });

  RenderResult result = options.raw ? gradient_raw_result(passes, thread_stats)
                                    : gradient_result(passes, thread_stats, m_settings.alpha,
                                                      m_settings.reconstruction, options, m_json);
  result.wall_seconds = timer.seconds();
  return result;
}

RenderResult GptIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
