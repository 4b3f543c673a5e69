// Per-sample physics of bidirectional path tracing (Veach 1997, Ch. 10): one camera
// subpath through a raster position and one light subpath, every strategy (s, t) with
// s + t - 1 <= max_depth connected and MIS-weighted (pathspace/bidir_mis.h). Camera-side
// strategies (t >= 2) add to the sample's radiance; light tracing (t = 1) produces splats
// for the pixels the light vertices project to. A sample with any non-finite value is
// dropped whole (radiance and splats) and reported to the caller. Grid media: delta
// tracking in the walks, ratio tracking on connections (pathspace/bidir_media.h).
#pragma once

#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/bdpt/bdpt_settings.h"
#include "integrators/bdpt/splat_merger.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

// Hot-loop counters, flushed into core::Stats once per tile.
struct BdptCounters {
  int64_t camera_vertices = 0, light_vertices = 0, connections = 0, occluded = 0, splats = 0;
  int64_t medium_vertices = 0;  // camera and light vertices in media
  int64_t media_skipped = 0;    // samples traced without medium code (scene without media)
  int64_t grid_flights = 0;     // free flights by delta tracking (grid media)
  int64_t ratio_tracking = 0;   // connection transmittances estimated by ratio tracking (grid media)
  void flush(core::Stats& stats) const {
    stats.add("bdpt.grid_flights", grid_flights);
    stats.add("bdpt.ratio_tracking", ratio_tracking);
    stats.add("bdpt.medium_vertices", medium_vertices);
    stats.add("bdpt.media_skipped", media_skipped);
    stats.add("bdpt.camera_vertices", camera_vertices);
    stats.add("bdpt.light_vertices", light_vertices);
    stats.add("bdpt.connections", connections);
    stats.add("bdpt.connections_occluded", occluded);
    stats.add("bdpt.splats", splats);
  }
};

// Per-thread scratch (no allocation per sample once warmed up).
struct BdptScratch {
  std::vector<pathspace::BidirVertex> camera, light;
  std::vector<Splat> pending;
};

class BdptTracer {
 public:
  BdptTracer(const scene::Scene& scene, const BdptSettings& settings, int max_depth);
  // Adds the camera-side estimate to L and appends splats (pixel index, value) to
  // `splats`; returns false (adding nothing) if any value was NaN/Inf.
  bool sample(const Vec2& raster, core::Rng& rng, BdptScratch& scratch, Rgb& L, std::vector<Splat>& splats,
              BdptCounters& counters) const;

 private:
  const scene::Scene& m_scene;
  BdptSettings m_settings;
  int m_max_depth;
  bool m_has_grid;  // some medium is a grid
};

}  // namespace dp::integrators
