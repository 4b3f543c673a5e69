#include "integrators/tile_scheduler.h"

#include <algorithm>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"

namespace dp::integrators {

int resolve_threads(const RenderOptions& options) {
  return options.threads > 0 ? options.threads : core::hardware_threads();
}

int64_t ScheduleResult::min_spp() const {
  return tile_spp.empty() ? 0 : *std::min_element(tile_spp.begin(), tile_spp.end());
}
int64_t ScheduleResult::max_spp() const {
  return tile_spp.empty() ? 0 : *std::max_element(tile_spp.begin(), tile_spp.end());
}
int64_t ScheduleResult::spp_at(int x, int y) const {
  return tile_spp[size_t((y / kTileSize) * tiles_x + x / kTileSize)];
}

ScheduleResult run_tiles(int width, int height, const RenderOptions& options, const std::string& label,
                         const TileFunction& fn) {
  ScheduleResult result;
  const int tx = (width + kTileSize - 1) / kTileSize, ty = (height + kTileSize - 1) / kTileSize;
  result.tiles_x = tx;
  for (int y = 0; y < ty; ++y)
    for (int x = 0; x < tx; ++x) {
      Tile t;
      t.index = y * tx + x;
      t.x0 = x * kTileSize;
      t.y0 = y * kTileSize;
      t.x1 = std::min(width, t.x0 + kTileSize);
      t.y1 = std::min(height, t.y0 + kTileSize);
      result.tiles.push_back(t);
    }
  result.tile_spp.assign(result.tiles.size(), 0);
  const bool timed = options.time_budget > 0;
  const int threads = resolve_threads(options);
  const int pass_spp = timed ? 1 : std::max(1, options.spp);
  const int64_t total_passes = timed ? 0 : 1;
  core::Timer timer;
  core::Progress progress(label, timed ? 1000 : int64_t(result.tiles.size()), options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  for (int64_t pass = 0; timed || pass < total_passes; ++pass) {
    if (should_stop()) break;
    core::parallel_for(
        int64_t(result.tiles.size()), threads,
        [&](int64_t item, int thread) {
          if (should_stop()) {
            stop.store(true);
            return;
          }
          const Tile& tile = result.tiles[size_t(item)];
          core::Rng rng(options.seed, core::mix64(uint64_t(pass) * 0x100000001b3ull + uint64_t(tile.index)));
          fn(tile, pass_spp, rng, thread);
          result.tile_spp[size_t(item)] += pass_spp;  // each tile index is owned by one worker
          if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
          else progress.advance();
        },
        &stop);
    ++result.passes;
    if (stop.load()) break;
  }
  progress.finish();
  result.seconds = timer.seconds();
  const bool interrupted = options.stop && options.stop->load();
  result.partial = interrupted || (!timed && result.min_spp() < pass_spp);
  return result;
}

}  // namespace dp::integrators
