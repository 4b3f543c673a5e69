// The end of a tile-scheduled render whose accumulation buffers are raw sums (issue 17):
// with RenderOptions::raw the buffers themselves (for `--partial` and `--mpi`), else the
// integrator's finish() on them -- the very code a `merge` of partial files runs, so a
// merged render and a single one give the same bits -- plus the schedule's facts.
#pragma once

#include <functional>
#include <vector>

#include "core/raw_image.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

// The schedule's per-pixel sample counts (the raw count "spp").
std::vector<int64_t> spp_counts(const ScheduleResult& sched, int width, int height);

// The end of a finish(): min_spp/max_spp of `count`, partial = min_spp < options.spp, and
// (as ScheduleResult::fill) an "spp" layer of the counts where pixels lack samples.
void fill_counts(const std::vector<int64_t>& count, int width, int height, const RenderOptions& options,
                 RenderResult& result);

// finish() with spp 0 for a time budget (no count to fall short of); wall time, spp range,
// partial and passes from the schedule; the "spp" layer of an interrupted render.
using FinishFunction = std::function<RenderResult(const core::RawImage& raw, const RenderOptions& options)>;
RenderResult finish_tiled(const FinishFunction& finish, core::RawImage raw, const ScheduleResult& sched,
                          const RenderOptions& options);

// The end of a progressive render (photon iterations) with one radiance buffer: `total`
// becomes the raw "radiance" sums with "spp" = `done` iterations in every pixel, then the
// raw buffers (RenderOptions::raw) or finish() (spp 0 under a time budget); spp range and
// partial = stopped, or fewer than `target` iterations in --spp mode.
RenderResult finish_iterations(const FinishFunction& finish, int width, int height, std::vector<Rgbd>&& total,
                               int64_t done, int64_t target, bool stopped, const RenderOptions& options);

}  // namespace dp::integrators
