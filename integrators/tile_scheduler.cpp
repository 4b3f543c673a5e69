#include "integrators/tile_scheduler.h"

#include <algorithm>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"

namespace dp::integrators {

int resolve_threads(const RenderOptions& options) {
  return options.threads > 0 ? options.threads : core::hardware_threads();
}

void ScheduleResult::fill(RenderResult& result) const {
  result.wall_seconds = seconds;
  result.min_spp = min_spp();
  result.max_spp = max_spp();
  result.partial = partial;
  result.info["passes"] = passes;
  // Which pixels an interrupted (or time-cut) render lacks: their sample counts.
  if (partial || result.min_spp != result.max_spp) result.layers.push_back({"spp", spp_image()});
}

core::Image ScheduleResult::spp_image() const {
  int width = 0, height = 0;
  for (const Tile& t : tiles) {
    width = std::max(width, t.x1);
    height = std::max(height, t.y1);
  }
  core::Image image(width, height);
  for (const Tile& t : tiles)
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) image(x, y) = Rgb::Constant(float(tile_spp[size_t(t.index)]));
  return image;
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

int progressive_pass_spp(int spp, int64_t pass) {
  // Pass sizes 1, 1, 2, 4, ..., kMaxPassSpp, kMaxPassSpp, ... (the totals double until the
  // cap), the last pass takes the rest. The cap bounds how long a Ctrl-C waits for the
  // tiles in flight (one tile-pass) and the uneven sample counts an interruption leaves.
  int64_t done = 0, size = 1;
  for (int64_t p = 0; p < pass && done < spp; ++p) {
    done += size;
    if (p > 0) size = std::min<int64_t>(2 * size, kMaxPassSpp);
  }
  return int(std::clamp<int64_t>(int64_t(spp) - done, 0, size));
}

ScheduleResult run_tiles(int width, int height, const RenderOptions& options, const std::string& label,
                         const TileFunction& fn, const PassFunction& pass_done) {
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
  const int spp = timed ? 1 : std::max(1, options.spp);
  core::Timer timer;
  core::Progress progress(label, timed ? 1000 : int64_t(result.tiles.size()) * spp, options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  for (int64_t pass = 0;; ++pass) {
    const int pass_spp = timed ? 1 : progressive_pass_spp(spp, pass);
    if (pass_spp == 0 || should_stop()) break;
    std::atomic<int64_t> tiles_done{0};
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
          tiles_done.fetch_add(1);
          if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
          else progress.advance(pass_spp);
        },
        &stop);
    ++result.passes;
    if (pass_done) pass_done(pass, tiles_done.load() == int64_t(result.tiles.size()));
    if (stop.load()) break;
  }
  progress.finish();
  result.seconds = timer.seconds();
  const bool interrupted = options.stop && options.stop->load();
  result.partial = interrupted || (!timed && result.min_spp() < spp);
  return result;
}

}  // namespace dp::integrators
