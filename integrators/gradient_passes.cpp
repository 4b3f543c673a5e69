#include "integrators/gradient_passes.h"

#include <algorithm>
#include <vector>

#include "core/timer.h"
#include "integrators/gradient_output.h"

namespace dp::integrators {

GradientPasses render_gradient_passes(int w, int h, const RenderOptions& options, const std::string& label,
                                      const GradientTileFunction& fn) {
  check_parts(w, h, options);
  const int threads = resolve_threads(options);
  std::vector<gradients::GradientBuffers> buffers(size_t(threads), gradients::GradientBuffers(w, h));
  GradientPasses out;
  out.total = gradients::GradientBuffers(w, h);
  auto commit = [&](bool complete) {
    for (auto& b : buffers) {
      if (complete) out.total.merge(b);
      b.clear();
    }
    out.kept += complete ? 1 : 0;
  };
  auto tile_fn = [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
    fn(tile, spp, rng, thread, buffers[size_t(thread)]);
  };
  core::Timer timer;
  RenderOptions pass_opt = options;
  pass_opt.time_budget = 0;
  if (options.time_budget > 0) {
    pass_opt.spp = 1;
    pass_opt.quiet = true;
    do {
      // A time-budgeted part k of n takes the seeds of passes k, n + k, 2n + k, ... of the
      // single render (tile_scheduler.h), and each of its passes is whole (no split).
      pass_opt.seed = timed_pass_seed(options, out.passes);
      pass_opt.part = 0;
      pass_opt.parts = 1;
      const ScheduleResult sched = run_tiles(w, h, pass_opt, label, tile_fn);
      ++out.passes;
      commit(!sched.partial);
      if (sched.partial) out.partial = true;
    } while (!out.partial && timer.seconds() < options.time_budget && !(options.stop && options.stop->load()));
  } else {
    // Progressive passes (tile_scheduler.h); only complete ones are kept.
    const ScheduleResult sched =
        run_tiles(w, h, pass_opt, label, tile_fn, [&](int64_t, bool complete) { commit(complete); });
    out.passes = sched.passes;
    out.partial = sched.partial;
  }
  // Ctrl-C between two passes of a --time render stops it early too.
  out.partial |= options.stop && options.stop->load();
  out.render_seconds = timer.seconds();
  return out;
}

RenderResult gradient_result(const GradientPasses& passes, const std::vector<core::Stats>& thread_stats, float alpha,
                             const std::string& reconstruction, const RenderOptions& options,
                             const core::Json& settings) {
  RenderResult result;
  for (const auto& s : thread_stats) result.stats.merge(s);
  // Screened Poisson reconstruction without the direct layer (Lehtinen 2013, Eq. 8;
  // Kettunen 2015, Sec. 6; Manzi 2015, Sec. 5), which is added back afterwards.
  const gradients::GradientBuffers& total = passes.total;
  add_gradient_layers(total.primal(), total.dx(), total.dy(), total.direct(), alpha, reconstruction, options, result);
  passes.fill(result);
  result.info["settings"] = settings;
  return result;
}

uint64_t timed_pass_seed(const RenderOptions& options, int64_t pass) {
  return core::mix64(options.seed * 0x9e3779b97f4a7c15ull + uint64_t(timed_pass(options, pass)));
}

RenderResult gradient_raw_result(const GradientPasses& passes, const std::vector<core::Stats>& thread_stats) {
  RenderResult result;
  for (const auto& s : thread_stats) result.stats.merge(s);
  result.raw = passes.total.to_raw();
  passes.fill(result);
  return result;
}

GradientPasses gradient_passes_from_raw(const core::RawImage& raw, int spp) {
  GradientPasses passes;
  passes.total = gradients::GradientBuffers::from_raw(raw);
  for (const int64_t n : raw.count("spp")) passes.partial |= n < spp;
  return passes;
}

void GradientPasses::fill(RenderResult& result) const {
  const int w = total.width(), h = total.height();
  int64_t lo = w > 0 && h > 0 ? total.samples(0, 0) : 0, hi = lo;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      lo = std::min(lo, total.samples(x, y));
      hi = std::max(hi, total.samples(x, y));
    }
  result.min_spp = lo;
  result.max_spp = hi;
  result.partial |= partial;  // an interrupted reconstruction (gradient_output.h) is partial too
  result.info["passes"] = passes;
  result.info["passes_kept"] = kept;
  result.info["render_seconds"] = render_seconds;
}

RenderResult gradient_finish(const core::RawImage& raw, const RenderOptions& options, float alpha,
                             const std::string& reconstruction, const core::Json& settings) {
  core::Timer timer;
  RenderResult result =
      gradient_result(gradient_passes_from_raw(raw, options.spp), {}, alpha, reconstruction, options, settings);
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace dp::integrators
