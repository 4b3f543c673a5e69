// Tiled, pass-based scheduling shared by the Monte Carlo integrators.
// The image is cut into 16x16 tiles. A fixed-spp render is progressive: passes over
// every tile of 1, 1, 2, 4, ..., 64, 64, ... samples per pixel (the totals double up to
// the cap, the last pass takes the rest), so an interrupted render (Ctrl-C) is the whole image at
// fewer samples, not a finished part and a black rest. A time-budgeted render runs
// passes of one sample per pixel until the wall-clock budget (steady_clock) is used up.
// Every (pass, tile) gets its own random stream derived from (seed, pass, tile), so
// results depend only on the seed — not on the thread count or scheduling. Stopping
// (Ctrl-C or budget) happens at tile boundaries: a tile is either fully rendered for a
// pass or not at all, and its sample count says so. `pass_done(pass, complete)` (optional)
// runs after each pass on the calling thread; complete = every tile rendered it
// (integrators that need whole passes, e.g. G-PT's pair estimates, commit only those).
// Shares (`render --part K/N`, issue 17): the work units of a fixed-spp render are its
// (pass, tile) pairs; part k of n renders unit (pass, tile) iff (pass * tiles + tile) % n
// == k, with the unit's usual stream. The n parts together take every sample of the
// whole render exactly once, with the same random numbers, so their summed raw buffers
// hold the same samples (added in another order: equal up to double rounding). Passes
// without a unit of this part are skipped (no pass_done); `complete` means every unit of
// this part in the pass was rendered. A time-budgeted part renders every tile in its 1-spp
// passes, its pass p drawing the streams of pass p * n + k of a single time-budgeted
// render (timed_pass): parts never share a stream, and parts that all reach P passes sum
// to exactly the single render that reached n * P passes.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/rng.h"
#include "integrators/integrator.h"

namespace dp::integrators {

struct Tile {
  int index = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
};

struct ScheduleResult {
  std::vector<int64_t> tile_spp;  // samples per pixel rendered in each tile
  std::vector<Tile> tiles;
  int64_t passes = 0;
  bool partial = false;  // stopped before the spp target (time budgets are never partial)
  double seconds = 0;
  int64_t min_spp() const;
  int64_t max_spp() const;
  // Per-pixel sample count image helper.
  int64_t spp_at(int x, int y) const;
  // The per-pixel sample counts as an image (every channel).
  core::Image spp_image() const;
  // Copies wall time, min/max spp, `partial` and info["passes"] into a render result, and
  // appends the layer "spp" (spp_image) when the render is partial or its counts differ
  // between pixels (a time budget ending inside a pass), so the image says what it lacks.
  void fill(RenderResult& result) const;
  int tiles_x = 0;
};

// fn(tile, spp, rng, thread): render `spp` samples for every pixel of the tile.
// `thread` indexes per-thread scratch state (0 .. threads-1).
using TileFunction = std::function<void(const Tile& tile, int spp, core::Rng& rng, int thread)>;

constexpr int kTileSize = 16;
constexpr int kMaxPassSpp = 64;  // largest progressive pass (samples per pixel)

using PassFunction = std::function<void(int64_t pass, bool complete)>;

// The per-pixel loop of a tile: `spp` jittered raster positions per pixel, each handed
// to sample(raster, L) -> false to drop the sample (a non-finite value: counted, never
// added); the pixel's sum of kept values is added to sum[y * width + x]. Returns the
// number of dropped samples.
template <class SampleFn>
int64_t accumulate_tile(const Tile& tile, int spp, core::Rng& rng, int width, std::vector<Rgbd>& sum,
                        SampleFn&& sample) {
  int64_t dropped = 0;
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      Rgbd acc = Rgbd::Zero();
      for (int s = 0; s < spp; ++s) {
        const Vec2 raster(float(x) + rng.uniform(), float(y) + rng.uniform());
        Rgb L = Rgb::Zero();
        if (!sample(raster, L)) {
          ++dropped;
          continue;
        }
        acc += L.cast<double>();
      }
      sum[size_t(y) * size_t(width) + size_t(x)] += acc;
    }
  return dropped;
}

// The tile of a camera-path tracer (path, volpath, bdpt): accumulate_tile over
// sample(raster, L, counters) with one Counters per tile, then counters.flush(stats) and
// the counters "<prefix>.paths" and "<prefix>.nan_dropped".
template <class Counters, class SampleFn>
void trace_tile(const Tile& tile, int spp, core::Rng& rng, int width, std::vector<Rgbd>& sum, core::Stats& stats,
                const std::string& prefix, SampleFn&& sample) {
  Counters counters;
  const int64_t dropped =
      accumulate_tile(tile, spp, rng, width, sum, [&](const Vec2& raster, Rgb& L) { return sample(raster, L, counters); });
  counters.flush(stats);
  stats.add(prefix + ".paths", int64_t(spp) * (tile.x1 - tile.x0) * (tile.y1 - tile.y0));
  stats.add(prefix + ".nan_dropped", dropped);
}

ScheduleResult run_tiles(int width, int height, const RenderOptions& options, const std::string& label,
                         const TileFunction& fn, const PassFunction& pass_done = {});

// Samples per pixel of pass `pass` of a progressive render of `spp` in all (0 = no more).
int progressive_pass_spp(int spp, int64_t pass);

// The pass whose streams pass `pass` of a time-budgeted part uses (see above).
int64_t timed_pass(const RenderOptions& options, int64_t pass);
// Whether part options.part of options.parts renders work unit (pass, tile) of a fixed-spp
// render (see above; always true with a time budget).
bool owns_unit(const RenderOptions& options, int64_t pass, int tile, int tiles);
// The number of work units (passes x tiles) of a fixed-spp render of `spp`: at most this
// many parts can each get a share. check_parts throws dp::ValueError when options ask for
// a part that does not exist or, with --spp, for more parts than units.
int64_t work_units(int width, int height, int spp);
void check_parts(int width, int height, const RenderOptions& options);

// Threads that run_tiles will use for these options.
int resolve_threads(const RenderOptions& options);

}  // namespace dp::integrators
