// First half of a VCM iteration (Georgiev et al. 2012, Sec. 5; SmallVCM's structure):
// one light subpath per pixel, traced in fixed chunks of paths, each chunk on its own
// random stream (seed, iteration, chunk), so the stored paths and the image are the same
// for any thread count. Every vertex is kept (camera path p connects to light path p),
// with its VCM prefix quantities (pathspace/vcm_mis.h); vertices a merge can use (y_j,
// j >= 1, non-Dirac surface) are photons (LightPathStore::collect_photons). Light tracing (t = 1) is evaluated
// here and its splats are merged in chunk order.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "integrators/bdpt/splat_merger.h"
#include "integrators/vcm/vcm_settings.h"
#include "pathspace/vcm_mis.h"

namespace dp::integrators {

// A light vertex a merge can use, with everything VCM's merge reads (no access to the
// stored paths): throughput, MIS record, path depth j; `path` locates it for the
// gradient-domain merges, which shift the photon's light subpath (it is light[depth] of
// LightPathStore::path(path)).
struct VcmPhoton {
  pathspace::VcmPhotonMis mis;
  Rgb beta = Rgb::Zero();
  int32_t depth = 0;
  uint32_t path = 0;
};

struct VcmLightCounters {
  int64_t light_vertices = 0, connections = 0, occluded = 0, splats = 0, nan_dropped = 0;
  VcmLightCounters& operator+=(const VcmLightCounters& o) {
    light_vertices += o.light_vertices;
    connections += o.connections;
    occluded += o.occluded;
    splats += o.splats;
    nan_dropped += o.nan_dropped;
    return *this;
  }
};

// The light paths of one chunk (kLightChunk consecutive paths), reused across iterations
// (cleared, capacity kept: no page faults per iteration).
struct LightChunk {
  std::vector<pathspace::BidirVertex> vertices;
  std::vector<pathspace::VcmPrefix> prefixes;  // parallel to vertices
  std::vector<uint32_t> start;                 // local path i: vertices [start[i], start[i + 1])
  uint32_t photon_count = 0;  // vertices that are photons (LightPathStore::collect_photons)
  std::vector<Splat> splats;
  VcmLightCounters counters;
  bool done = false;
  void clear();
};

constexpr int64_t kLightChunk = 1024;  // light paths per work item

struct LightPathStore {
  std::vector<LightChunk> chunks;
  std::vector<VcmPhoton> photons;  // every chunk's, in the grid's slot order (gather_photons)
  std::vector<Vec3> photon_pos;    // every chunk's, in chunk order (the grid's input)
  int64_t path_count = 0;
  int max_depth = 0;               // of the last light pass (photons are y_j, j < max_depth)
  float min_merge_roughness = 0;   // of the last light pass (pathspace::VcmMisConfig)
  size_t paths() const { return size_t(path_count); }
  // Light path p: its vertices and prefixes, and its length.
  const pathspace::BidirVertex* path(int64_t p, const pathspace::VcmPrefix** prefixes, int* length) const {
    const LightChunk& c = chunks[size_t(p / kLightChunk)];
    const size_t i = size_t(p % kLightChunk);
    *prefixes = c.prefixes.data() + c.start[i];
    *length = int(c.start[i + 1] - c.start[i]);
    return c.vertices.data() + c.start[i];
  }
  // Lists every photon of the stored paths (chunk order) into photons and photon_pos, in
  // one allocation each (chunks fill their slices in parallel).
  void collect_photons(int threads);
  // Reorders `photons` into the grid's slot order, in place: photons[k] = the photon
  // listed at order[k].
  void gather_photons(const std::vector<uint32_t>& order);
  // Frees `photons` and `photon_pos` (between iterations: the next light pass's peak
  // memory does not hold the last iteration's photons).
  void release_photons();
};

struct VcmIteration {
  int64_t index = 0;            // 0-based iteration
  uint64_t seed = 0;
  int max_depth = 8;
  pathspace::VcmMisConfig mis;
  float radius = 0;             // merging radius of this iteration
  bool light_tracing = true;    // false: the light pass does not splat (G-VCM light-traces per pixel)
};

// Traces `paths` light subpaths into `out` (its chunks; photons counted per chunk when the
// mode merges, listed by LightPathStore::collect_photons); returns false if `stop`
// interrupted it.
bool trace_light_paths(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it, int64_t paths,
                       int threads, const std::atomic<bool>* stop, LightPathStore& out, VcmLightCounters& counters);

}  // namespace dp::integrators
