// Whole-pass driver of the gradient-domain Monte Carlo integrators (G-PT, G-BDPT): the
// symmetric pair estimates need the same sample count in both pixels of a pair, so only
// complete passes are kept. Each thread owns a full-image gradients::GradientBuffers
// (pairs and light-tracing splats cross tile borders); a complete pass is merged into the
// total, an interrupted one (Ctrl-C) is dropped, so a partial render is the whole image at
// the samples of its complete passes. A time budget runs 1-spp passes until it is used up.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/stats.h"

#include "gradients/gradient_buffers.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

struct GradientPasses {
  gradients::GradientBuffers total;
  int64_t passes = 0, kept = 0;
  bool partial = false;
  double render_seconds = 0;
  // min/max spp, partial, info passes / passes_kept / render_seconds into `result`.
  void fill(RenderResult& result) const;
};

// fn(tile, spp, rng, thread, buffers): render `spp` samples per pixel of the tile into the
// thread's buffers.
using GradientTileFunction =
    std::function<void(const Tile& tile, int spp, core::Rng& rng, int thread, gradients::GradientBuffers& buf)>;

// The end of a pass render: merged counters, the reconstruction layers (gradient_output.h:
// screened Poisson L1 and L2 without the direct layer, which is added back), fill() and
// info["settings"] = settings. The caller sets wall_seconds (solves included).
RenderResult gradient_result(const GradientPasses& passes, const std::vector<core::Stats>& thread_stats, float alpha,
                             const std::string& reconstruction, const RenderOptions& options,
                             const core::Json& settings);

// `render --partial` (options.raw): the raw buffers (GradientBuffers::to_raw), merged
// counters and fill(), without the reconstruction.
RenderResult gradient_raw_result(const GradientPasses& passes, const std::vector<core::Stats>& thread_stats);
// `merge`: the passes of summed raw buffers (partial when a pixel has fewer than `spp`
// samples), ready for gradient_result.
GradientPasses gradient_passes_from_raw(const core::RawImage& raw, int spp);
// finish() of the pass-rendered gradient integrators (gpt, gbdpt): gradient_result of the
// summed raw buffers, wall_seconds = its own time.
RenderResult gradient_finish(const core::RawImage& raw, const RenderOptions& options, float alpha,
                             const std::string& reconstruction, const core::Json& settings);

// The seed of 1-spp pass `pass` of a time-budgeted render (or of part options.part of
// options.parts of one: the seed of the single render's pass timed_pass(options, pass)).
uint64_t timed_pass_seed(const RenderOptions& options, int64_t pass);

// Throws dp::ValueError for options.part/parts this driver cannot honour (tile_scheduler.h).
GradientPasses render_gradient_passes(int width, int height, const RenderOptions& options, const std::string& label,
                                      const GradientTileFunction& fn);

}  // namespace dp::integrators
