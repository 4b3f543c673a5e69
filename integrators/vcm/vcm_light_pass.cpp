#include "integrators/vcm/vcm_light_pass.h"

#include <algorithm>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

namespace {

constexpr int64_t kChunk = 1024;  // light paths per work item

struct Chunk {
  std::vector<pathspace::BidirVertex> vertices;
  std::vector<pathspace::VcmPrefix> prefixes;
  std::vector<uint32_t> length;
  std::vector<Splat> splats;
  VcmLightCounters counters;
};

// Light tracing of one light path: every y_{s-1} connected to the pinhole z_0.
void light_trace(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it,
                 const std::vector<pathspace::BidirVertex>& path, const std::vector<pathspace::VcmPrefix>& pre,
                 const pathspace::BidirVertex& z0, Chunk& chunk) {
  const pathspace::VcmPrefix z0_prefix{};
  const int width = scene.camera().width(), height = scene.camera().height();
  const size_t first = chunk.splats.size();
  bool finite = true;
  for (int s = 1; s <= int(path.size()) && s <= it.max_depth; ++s) {
    pathspace::Connection c;
    const bool ok = pathspace::connect(scene, path.data(), s, &z0, 1, pathspace::MisConfig{.unweighted = true}, c);
    chunk.counters.connections += c.tested;
    chunk.counters.occluded += c.occluded;
    if (!ok) continue;
    const float w = settings.mode == VcmMode::lt
                        ? 1.0f
                        : pathspace::vcm_connection_weight(scene, path.data(), pre.data(), s, &z0, &z0_prefix, 1, it.mis);
    const Rgb v = c.value * w;
    if (is_black(v)) continue;
    finite = finite && is_finite(v);
    const int px = std::min(int(c.raster.x()), width - 1), py = std::min(int(c.raster.y()), height - 1);
    chunk.splats.push_back(Splat{py * width + px, v});
  }
  if (!finite) {  // the whole light path's splats are dropped, counted
    chunk.splats.resize(first);
    ++chunk.counters.nan_dropped;
  }
}

}  // namespace

bool trace_light_paths(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it, int64_t paths,
                       int threads, const std::atomic<bool>* stop, LightPathStore& out, VcmLightCounters& counters) {
  const int64_t chunks = (paths + kChunk - 1) / kChunk;
  std::vector<Chunk> result(static_cast<size_t>(chunks));
  std::vector<char> done(static_cast<size_t>(chunks), 0);
  const pathspace::SubpathParams params{it.max_depth, settings.rr_depth};
  std::vector<pathspace::BidirVertex> z0;
  core::Rng unused;
  pathspace::camera_subpath(scene, Vec2(0, 0), pathspace::SubpathParams{1, settings.rr_depth}, unused, z0);
  core::parallel_for(
      chunks, threads,
      [&](int64_t c, int) {
        Chunk& chunk = result[size_t(c)];
        core::Rng rng(it.seed, (uint64_t(it.index) << 32) | uint64_t(c));
        std::vector<pathspace::BidirVertex> path;
        std::vector<pathspace::VcmPrefix> pre;
        const int64_t end = std::min(paths, (c + 1) * kChunk);
        for (int64_t p = c * kChunk; p < end; ++p) {
          pathspace::light_subpath(scene, params, rng, path);
          pre.resize(path.size());
          pathspace::vcm_prefixes(path.data(), int(path.size()), false, it.mis, pre.data());
          if (settings.light_traces()) light_trace(scene, settings, it, path, pre, z0[0], chunk);
          chunk.vertices.insert(chunk.vertices.end(), path.begin(), path.end());
          chunk.prefixes.insert(chunk.prefixes.end(), pre.begin(), pre.end());
          chunk.length.push_back(uint32_t(path.size()));
          chunk.counters.light_vertices += int64_t(path.size());
        }
        done[size_t(c)] = 1;
      },
      stop);
  if (std::find(done.begin(), done.end(), 0) != done.end()) return false;

  out = LightPathStore{};
  size_t total = 0;
  for (const Chunk& c : result) total += c.vertices.size();
  out.vertices.reserve(total);
  out.prefixes.reserve(total);
  out.start.reserve(size_t(paths) + 1);
  out.start.push_back(0);
  const bool photons = settings.merges();
  for (Chunk& c : result) {
    size_t v = out.vertices.size();
    for (uint32_t len : c.length) {
      if (photons)
        for (uint32_t j = 1; j < len; ++j) {
          const pathspace::BidirVertex& y = c.vertices[v - out.vertices.size() + j];
          if (!pathspace::vcm_mergeable(y, false)) continue;
          out.photon_vertex.push_back(uint32_t(v + j));
          out.photon_depth.push_back(uint16_t(j));
          out.photon_pos.push_back(y.sp.p);
        }
      v += len;
      out.start.push_back(uint32_t(v));
    }
    out.vertices.insert(out.vertices.end(), c.vertices.begin(), c.vertices.end());
    out.prefixes.insert(out.prefixes.end(), c.prefixes.begin(), c.prefixes.end());
    out.splats.insert(out.splats.end(), c.splats.begin(), c.splats.end());
    counters.light_vertices += c.counters.light_vertices;
    counters.connections += c.counters.connections;
    counters.occluded += c.counters.occluded;
    counters.splats += int64_t(c.splats.size());
    counters.nan_dropped += c.counters.nan_dropped;
    c = Chunk{};
  }
  return true;
}

}  // namespace dp::integrators
