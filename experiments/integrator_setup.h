// Creating a run's integrator: the scene's own `integrator:` settings apply only when
// the run uses the scene's integrator type; the run's `reconstruction` and `settings`
// are applied on top (as `--set` would). Errors (unknown integrator, unknown or bad
// setting) carry the experiment file and the run's line.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/json.h"
#include "integrators/integrator.h"
#include "scene/scene.h"

namespace dp::experiments {

struct PreparedIntegrator {
  std::unique_ptr<integrators::Integrator> integrator;
  core::Json settings = core::Json::object();  // every resolved setting (sidecars, hashes)
  std::string settings_text;                   // settings.dump(0), stable for hashing
};

PreparedIntegrator prepare_integrator(const scene::Scene& scene, const std::string& name,
                                      const std::vector<std::pair<std::string, std::string>>& settings,
                                      const std::string& file, int line);

// FNV-1a 64-bit hash (cache keys and resumability keys; not cryptographic).
uint64_t fnv1a(const std::string& bytes, uint64_t h = 0xcbf29ce484222325ull);
std::string hex64(uint64_t v);

}  // namespace dp::experiments
