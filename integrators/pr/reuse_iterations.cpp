#include "integrators/pr/reuse_iterations.h"

#include <algorithm>
#include <atomic>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/iteration_share.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

int64_t ReuseSchedule::min_count() const { return count.empty() ? 0 : *std::min_element(count.begin(), count.end()); }
int64_t ReuseSchedule::max_count() const { return count.empty() ? 0 : *std::max_element(count.begin(), count.end()); }

ReuseSchedule run_reuse_iterations(int w, int h, int tile_size, const RenderOptions& options, const std::string& label,
                                   const ReuseTileFunction& fn, bool jitter) {
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const IterationShare share(options, 1);  // every pixel gets a sample
  const int64_t target = share.target;
  ReuseSchedule out;
  out.count.assign(size_t(w) * size_t(h), 0);
  core::Timer timer;
  core::Progress progress(label, timed ? 1000 : target, options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  for (int64_t k = 0; timed || k < target; ++k) {
    const int64_t it = share.global(k);
    const bool first = k == 0;  // always completes: every pixel gets a sample
    if (!first && should_stop()) break;
    const ReuseTiling tiling = jittered_tiling(w, h, tile_size, options.seed, it, jitter);
    core::parallel_for(
        int64_t(tiling.tiles.size()), threads,
        [&](int64_t item, int thread) {
          if (!first && should_stop()) {
            stop.store(true);
            return;
          }
          const ReuseTile& tile = tiling.tiles[size_t(item)];
          core::Rng rng(options.seed, core::mix64(uint64_t(it) * 0x9e3779b97f4a7c15ull + uint64_t(item)));
          fn(tile, rng, thread);  // tiles are disjoint: no two workers share a pixel
          for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) ++out.count[size_t(y) * size_t(w) + size_t(x)];
        },
        &stop);
    ++out.iterations;
    if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
    else progress.advance(1);
    if (stop.load()) break;
  }
  progress.finish();
  out.interrupted = options.stop && options.stop->load();
  out.partial = out.interrupted || (!timed && out.iterations < target);
  out.seconds = timer.seconds();
  return out;
}

}  // namespace dp::integrators
