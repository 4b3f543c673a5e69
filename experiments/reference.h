// The experiment's reference image: either a file ({file: ref.exr}; EXR, PNG...) or a
// render ({integrator: path, spp: 65536}) made once and cached as
// <cache_dir>/<integrator>-<spp>spp-<hash>.exr. The hash covers the scene file's bytes,
// the integrator, its resolved settings, spp, max_depth and the reference seed, so
// editing the scene file or settings renders a new reference; files the scene refers to
// (meshes, textures) are not hashed. The reference is rendered with the seed
// kReferenceSeed, which no run uses (runs use seeds 0 .. seeds-1), so its noise is
// independent of theirs.
#pragma once

#include <atomic>
#include <string>

#include "core/image.h"
#include "experiments/config.h"
#include "scene/scene.h"

namespace dp::experiments {

constexpr uint64_t kReferenceSeed = 0x5245464552454e43ull;  // "REFERENC"

struct RenderContext {
  int threads = 0;  // 0 = all cores
  bool quiet = false;
  const std::atomic<bool>* stop = nullptr;  // Ctrl-C
};

struct Reference {
  core::Image image;
  std::string path;       // file read, or the cache file
  bool rendered = false;  // rendered by this call (not read from file or cache)
};

// Cache file name (inside cache_dir) a {integrator, spp} reference would use.
std::string reference_cache_name(const ExperimentConfig& config, const scene::Scene& scene);

// Reads or renders the reference; checks that it matches the camera resolution.
Reference obtain_reference(const ExperimentConfig& config, const scene::Scene& scene, const RenderContext& ctx,
                           const std::string& cache_dir);

}  // namespace dp::experiments
