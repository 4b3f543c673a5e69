// Iteration driver of the path-reusing integrators (`pr`, `gpr`; Bauszat et al. 2017,
// Sec. 3.3): iterations over jittered T x T tilings (reuse_tiling.h), the tiles of one
// iteration in parallel. `--spp N` runs N iterations, `--time S` iterations until the
// budget is used up (steady_clock); the first iteration always completes, later ones stop
// at tile boundaries (Ctrl-C or budget). Tile `item` of iteration `it` draws from the
// stream (seed, mix(it, item)), so a render depends only on the seed, not on the thread
// count. Part k of n (RenderOptions::part/parts: `render --partial --part`, `--mpi`) runs
// the global iterations k, k + n, ... with those iterations' tilings and streams, so the
// parts together do exactly the single render's work. The tiles of one iteration are disjoint: a tile function may write the pixels of
// its tile (for `gpr`: the gradient pairs whose first pixel is in it) without locking.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/rng.h"
#include "integrators/integrator.h"
#include "integrators/pr/reuse_tiling.h"

namespace dp::integrators {

struct ReuseSchedule {
  int64_t iterations = 0;        // iterations started (the last may be incomplete)
  std::vector<int64_t> count;    // per pixel (row-major): iterations whose tile rendered it
  bool interrupted = false;      // stopped by options.stop
  bool partial = false;          // interrupted, or fewer than this part's share of --spp
  double seconds = 0;            // wall time of the iterations
  int64_t min_count() const;
  int64_t max_count() const;
};

// fn(tile, rng, thread): render one tile of one iteration.
using ReuseTileFunction = std::function<void(const ReuseTile& tile, core::Rng& rng, int thread)>;

// `jitter`: see jittered_tiling.
ReuseSchedule run_reuse_iterations(int width, int height, int tile, const RenderOptions& options,
                                   const std::string& label, const ReuseTileFunction& fn, bool jitter = true);

}  // namespace dp::integrators
