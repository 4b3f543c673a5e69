#include "integrators/vcm/vcm_light_pass.h"

#include <algorithm>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

namespace {

// Light tracing of one light path: every y_{s-1} connected to the pinhole z_0.
void light_trace(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it,
                 const std::vector<pathspace::BidirVertex>& path, const std::vector<pathspace::VcmPrefix>& pre,
                 const pathspace::BidirVertex& z0, LightChunk& chunk) {
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

// Is light[j] of a path a photon: y_j, 1 <= j < max_depth, a surface whose BSDF has a
// non-Dirac part (pathspace::vcm_mergeable).
bool is_photon(const pathspace::BidirVertex& y, size_t j, int max_depth, float min_roughness) {
  return j >= 1 && int(j) < max_depth && pathspace::vcm_mergeable(y, false, min_roughness);
}

}  // namespace

namespace {
// Empties v, keeping capacity for about 1/8 more than it held: chunk sizes vary by a few
// percent between iterations, and a vector grown by doubling would otherwise keep up to
// twice what it needs (the light store dominates VCM's memory: issue 13's budget).
template <class T>
void clear_with_headroom(std::vector<T>& v) {
  const size_t want = v.size() + v.size() / 8;
  if (v.capacity() > want + want / 4) {
    std::vector<T> fresh;
    fresh.reserve(want);
    v.swap(fresh);
  } else {
    v.clear();
  }
}
}  // namespace

void LightChunk::clear() {
  clear_with_headroom(vertices);
  clear_with_headroom(prefixes);
  start.clear();
  photon_count = 0;
  splats.clear();
  counters = VcmLightCounters{};
  done = false;
}

void LightPathStore::release_photons() {
  photons = {};
  photon_pos = {};
}

void LightPathStore::collect_photons(int threads) {
  std::vector<size_t> offset(chunks.size() + 1, 0);
  for (size_t c = 0; c < chunks.size(); ++c) offset[c + 1] = offset[c] + chunks[c].photon_count;
  photons.resize(offset.back());
  photon_pos.resize(offset.back());
  core::parallel_for(int64_t(chunks.size()), threads, [&](int64_t ci, int) {
    const LightChunk& c = chunks[size_t(ci)];
    size_t k = offset[size_t(ci)];
    for (size_t i = 0; i + 1 < c.start.size(); ++i)
      for (size_t j = 1; j < c.start[i + 1] - c.start[i]; ++j) {
        const size_t v = c.start[i] + j;
        if (!is_photon(c.vertices[v], j, max_depth, min_merge_roughness)) continue;
        VcmPhoton& ph = photons[k];
        ph.mis = pathspace::vcm_photon_mis(&c.vertices[c.start[i]], &c.prefixes[c.start[i]], int(j));
        ph.beta = c.vertices[v].beta;
        ph.depth = int32_t(j);
        ph.path = uint32_t(ci * kLightChunk + int64_t(i));
        photon_pos[k++] = c.vertices[v].sp.p;
      }
  });
}

void LightPathStore::gather_photons(const std::vector<uint32_t>& order) {
  // In place, cycle by cycle: photons[k] = (chunk order)[order[k]] (one copy resident).
  std::vector<bool> placed(photons.size(), false);
  for (size_t i = 0; i < photons.size(); ++i) {
    if (placed[i]) continue;
    const VcmPhoton first = photons[i];
    for (size_t j = i;;) {
      placed[j] = true;
      const size_t k = order[j];
      if (k == i) {
        photons[j] = first;
        break;
      }
      photons[j] = photons[k];
      j = k;
    }
  }
}

bool trace_light_paths(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it, int64_t paths,
                       int threads, const std::atomic<bool>* stop, LightPathStore& out, VcmLightCounters& counters) {
  const int64_t chunks = (paths + kLightChunk - 1) / kLightChunk;
  out.chunks.resize(size_t(chunks));
  out.path_count = paths;
  out.max_depth = it.max_depth;
  out.min_merge_roughness = it.mis.min_merge_roughness;
  const pathspace::SubpathParams params{it.max_depth, settings.rr_depth};
  std::vector<pathspace::BidirVertex> z0;
  core::Rng unused;
  pathspace::camera_subpath(scene, Vec2(0, 0), pathspace::SubpathParams{1, settings.rr_depth}, unused, z0);
  const bool photons = settings.merges();
  // The first pass sizes the chunks from chunk 0, traced alone (vectors grown by doubling
  // would hold up to twice what they need; chunk sizes differ by a few percent).
  const bool first_pass = chunks > 0 && out.chunks[0].vertices.capacity() == 0;
  size_t vertex_hint = 0;
  auto trace_chunk = [&](int64_t c) {
    LightChunk& chunk = out.chunks[size_t(c)];
    chunk.clear();
    if (chunk.vertices.capacity() < vertex_hint) {
      chunk.vertices.reserve(vertex_hint);
      chunk.prefixes.reserve(vertex_hint);
    }
    core::Rng rng(it.seed, (uint64_t(it.index) << 32) | uint64_t(c));
    std::vector<pathspace::BidirVertex> path;
    std::vector<pathspace::VcmPrefix> pre;
    const int64_t end = std::min(paths, (c + 1) * kLightChunk);
    chunk.start.push_back(0);
    for (int64_t p = c * kLightChunk; p < end; ++p) {
      pathspace::light_subpath(scene, params, rng, path);
      pre.resize(path.size());
      pathspace::vcm_prefixes(path.data(), int(path.size()), false, it.mis, pre.data());
      if (settings.light_traces() && it.light_tracing) light_trace(scene, settings, it, path, pre, z0[0], chunk);
      chunk.vertices.insert(chunk.vertices.end(), path.begin(), path.end());
      chunk.prefixes.insert(chunk.prefixes.end(), pre.begin(), pre.end());
      chunk.start.push_back(uint32_t(chunk.vertices.size()));
      chunk.counters.light_vertices += int64_t(path.size());
      if (photons)
        for (size_t j = 1; j < path.size(); ++j) chunk.photon_count += is_photon(path[j], j, it.max_depth, it.mis.min_merge_roughness);
    }
    chunk.counters.splats = int64_t(chunk.splats.size());
    chunk.done = true;
  };
  int64_t pilot = 0;
  if (first_pass) {
    trace_chunk(0);
    const size_t v = out.chunks[0].vertices.size();
    vertex_hint = v + v / 8;
    pilot = 1;
  }
  core::parallel_for(
      chunks - pilot, threads, [&](int64_t c, int) { trace_chunk(c + pilot); }, stop);
  for (const LightChunk& c : out.chunks) {
    if (!c.done) return false;
    counters += c.counters;
  }
  return true;
}

}  // namespace dp::integrators
