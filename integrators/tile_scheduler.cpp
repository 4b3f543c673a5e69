#include "integrators/tile_scheduler.h"

#include <algorithm>

#include "core/error.h"
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

int64_t timed_pass(const RenderOptions& options, int64_t pass) {
  return options.parts <= 1 ? pass : pass * int64_t(options.parts) + int64_t(options.part);
}

bool owns_unit(const RenderOptions& options, int64_t pass, int tile, int tiles) {
  if (options.parts <= 1 || options.time_budget > 0) return true;
  return (pass * int64_t(tiles) + int64_t(tile)) % int64_t(options.parts) == int64_t(options.part);
}

namespace {
// Calls fn(pass, pass_spp) for every pass of a progressive render of `spp` (the sizes of
// progressive_pass_spp, in time linear in the number of passes).
template <class Fn>
void for_each_pass(int spp, Fn&& fn) {
  int64_t done = 0, size = 1;
  for (int64_t pass = 0; done < spp; ++pass) {
    const int64_t n = std::min<int64_t>(size, int64_t(spp) - done);
    fn(pass, int(n));
    done += n;
    if (pass > 0) size = std::min<int64_t>(2 * size, kMaxPassSpp);
  }
}
}  // namespace

int64_t work_units(int width, int height, int spp) {
  int64_t passes = 0;
  for_each_pass(spp, [&](int64_t, int) { ++passes; });
  const int64_t tiles = int64_t((width + kTileSize - 1) / kTileSize) * int64_t((height + kTileSize - 1) / kTileSize);
  return passes * tiles;
}

void check_parts(int width, int height, const RenderOptions& options) {
  if (options.parts <= 1) return;
  const std::string part = std::to_string(options.part + 1) + "/" + std::to_string(options.parts);
  if (options.part < 0 || options.part >= options.parts) throw ValueError("part " + part + " does not exist");
  if (options.time_budget > 0) return;  // every part runs its own passes (timed_pass)
  const int64_t units = work_units(width, height, options.spp);
  if (options.parts > units)
    throw ValueError("part " + part + ": --spp " + std::to_string(options.spp) + " at " + std::to_string(width) + "x" +
                     std::to_string(height) + " has only " + std::to_string(units) +
                     " work units (passes x 16x16 tiles); use at most " + std::to_string(units) + " parts");
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
  check_parts(width, height, options);
  const bool timed = options.time_budget > 0;
  const int threads = resolve_threads(options);
  const int spp = timed ? 1 : std::max(1, options.spp);
  const int n_tiles = int(result.tiles.size());
  // Samples per pixel each tile should reach: spp, or this part's share of it.
  std::vector<int64_t> target(result.tiles.size(), 0);
  if (!timed)
    for_each_pass(spp, [&](int64_t pass, int pass_spp) {
      for (int t = 0; t < n_tiles; ++t)
        if (owns_unit(options, pass, t, n_tiles)) target[size_t(t)] += pass_spp;
    });
  int64_t work = 0;
  for (const int64_t t : target) work += t;
  core::Timer timer;
  core::Progress progress(label, timed ? 1000 : work, options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  for (int64_t pass = 0;; ++pass) {
    const int pass_spp = timed ? 1 : progressive_pass_spp(spp, pass);
    if (pass_spp == 0 || should_stop()) break;
    int64_t owned = 0;
    for (int t = 0; t < n_tiles; ++t) owned += owns_unit(options, pass, t, n_tiles) ? 1 : 0;
    if (owned == 0) continue;  // another part's pass
    std::atomic<int64_t> tiles_done{0};
    core::parallel_for(
        int64_t(result.tiles.size()), threads,
        [&](int64_t item, int thread) {
          if (!owns_unit(options, pass, int(item), n_tiles)) return;
          if (should_stop()) {
            stop.store(true);
            return;
          }
          const Tile& tile = result.tiles[size_t(item)];
          const int64_t stream_pass = timed ? timed_pass(options, pass) : pass;
          core::Rng rng(options.seed, core::mix64(uint64_t(stream_pass) * 0x100000001b3ull + uint64_t(tile.index)));
          fn(tile, pass_spp, rng, thread);
          result.tile_spp[size_t(item)] += pass_spp;  // each tile index is owned by one worker
          tiles_done.fetch_add(1);
          if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
          else progress.advance(pass_spp);
        },
        &stop);
    ++result.passes;
    if (pass_done) pass_done(pass, tiles_done.load() == owned);
    if (stop.load()) break;
  }
  progress.finish();
  result.seconds = timer.seconds();
  const bool interrupted = options.stop && options.stop->load();
  bool short_of_target = false;
  for (size_t t = 0; t < target.size(); ++t) short_of_target |= result.tile_spp[t] < target[t];
  result.partial = interrupted || (!timed && short_of_target);
  return result;
}

}  // namespace dp::integrators
