// First half of a VCM iteration (Georgiev et al. 2012, Sec. 5; SmallVCM's structure):
// one light subpath per pixel, traced in fixed chunks of paths, each chunk on its own
// random stream (seed, iteration, chunk), so the stored paths and the image are the same
// for any thread count. Every vertex is kept (camera path p connects to light path p),
// with its VCM prefix quantities (pathspace/vcm_mis.h); vertices a merge can use (y_j,
// j >= 1, non-Dirac surface) are listed as photons. Light tracing (t = 1) is evaluated
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

struct LightPathStore {
  std::vector<pathspace::BidirVertex> vertices;
  std::vector<pathspace::VcmPrefix> prefixes;  // parallel to vertices
  std::vector<uint32_t> start;                 // path p: vertices [start[p], start[p + 1])
  std::vector<uint32_t> photon_vertex;         // photon k: index into vertices
  std::vector<uint16_t> photon_depth;          // photon k: j (its index within its light path)
  std::vector<Vec3> photon_pos;
  std::vector<Splat> splats;                   // light tracing, in chunk order
  size_t paths() const { return start.empty() ? 0 : start.size() - 1; }
};

struct VcmLightCounters {
  int64_t light_vertices = 0, connections = 0, occluded = 0, splats = 0, nan_dropped = 0;
};

struct VcmIteration {
  int64_t index = 0;            // 0-based iteration
  uint64_t seed = 0;
  int max_depth = 8;
  pathspace::VcmMisConfig mis;
  float radius = 0;             // merging radius of this iteration
};

// Traces `paths` light subpaths into `out`; returns false if `stop` interrupted it.
bool trace_light_paths(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it, int64_t paths,
                       int threads, const std::atomic<bool>* stop, LightPathStore& out, VcmLightCounters& counters);

}  // namespace dp::integrators
