#include "integrators/gpt/gpt_integrator.h"

#include "core/rng.h"
#include "core/timer.h"
#include "gradients/gradient_buffers.h"
#include "integrators/gpt/gpt_tracer.h"
#include "integrators/gradient_output.h"
#include "integrators/tile_scheduler.h"
#include "pathspace/sample_stream.h"

namespace dp::integrators {

RenderResult GptIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  std::vector<gradients::GradientBuffers> buffers(size_t(threads), gradients::GradientBuffers(w, h));
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads));
  const GptTracer tracer(scene, m_settings, options.max_depth);

  auto tile_fn = [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
    pathspace::IndependentStream stream(rng);
    GptCounters counters;
    auto& buf = buffers[size_t(thread)];
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        for (int s = 0; s < spp; ++s) tracer.sample(x, y, stream, buf, counters);
    counters.flush(thread_stats[size_t(thread)]);
  };

  // Whole passes only: the symmetric pair estimates need equal counts in both pixels. A
  // pass's samples go to the per-thread buffers; a complete pass is moved into `total`,
  // an interrupted one (Ctrl-C) is dropped, so a partial render is the whole image at the
  // samples of its complete passes.
  gradients::GradientBuffers total(w, h);
  int64_t committed = 0;
  auto commit = [&](bool complete) {
    for (auto& b : buffers) {
      if (complete) total.merge(b);
      b.clear();
    }
    committed += complete ? 1 : 0;
  };
  core::Timer timer;
  RenderOptions pass_opt = options;
  pass_opt.time_budget = 0;
  int64_t passes = 0;
  bool partial = false;
  if (options.time_budget > 0) {
    pass_opt.spp = 1;
    pass_opt.quiet = true;
    do {
      pass_opt.seed = core::mix64(options.seed * 0x9e3779b97f4a7c15ull + uint64_t(passes));
      const ScheduleResult sched = run_tiles(w, h, pass_opt, "gpt", tile_fn);
      ++passes;
      commit(!sched.partial);
      if (sched.partial) partial = true;
    } while (!partial && timer.seconds() < options.time_budget && !(options.stop && options.stop->load()));
  } else {
    // Progressive passes (tile_scheduler.h); only complete ones are kept.
    const ScheduleResult sched =
        run_tiles(w, h, pass_opt, "gpt", tile_fn, [&](int64_t, bool complete) { commit(complete); });
    passes = sched.passes;
    partial = sched.partial;
  }
  // Ctrl-C between two passes of a --time render stops it early too.
  partial |= options.stop && options.stop->load();
  const double render_seconds = timer.seconds();

  RenderResult result;
  for (const auto& s : thread_stats) result.stats.merge(s);

  // Screened Poisson reconstruction without the direct layer (Lehtinen 2013, Eq. 8; Kettunen
  // 2015, Sec. 6), which is added back afterwards.
  add_gradient_layers(total.primal(), total.dx(), total.dy(), total.direct(), m_settings.alpha,
                      m_settings.reconstruction, threads, result);
  result.wall_seconds = timer.seconds();
  int64_t lo = total.samples(0, 0), hi = lo;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      lo = std::min(lo, total.samples(x, y));
      hi = std::max(hi, total.samples(x, y));
    }
  result.min_spp = lo;
  result.max_spp = hi;
  result.partial = partial;
  result.info["passes"] = passes;
  result.info["passes_kept"] = committed;
  result.info["render_seconds"] = render_seconds;
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
