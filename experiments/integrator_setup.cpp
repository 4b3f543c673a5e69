#include "experiments/integrator_setup.h"

#include <cstdio>

#include "core/error.h"

namespace dp::experiments {

PreparedIntegrator prepare_integrator(const scene::Scene& scene, const std::string& name,
                                      const std::vector<std::pair<std::string, std::string>>& settings,
                                      const std::string& file, int line) {
  const std::string origin = line > 0 ? file + ":" + std::to_string(line) : file;
  integrators::Settings s;
  const auto& defaults = scene.integrator_defaults();
  if (name == defaults.type)
    for (const auto& [k, v] : defaults.settings) s.set(k, v, scene.source().empty() ? "scene" : scene.source());
  for (const auto& [k, v] : settings) s.set(k, v, origin);
  PreparedIntegrator p;
  try {
    p.integrator = integrators::make_integrator(name, s);
    integrators::check_scene_support(*p.integrator, scene);
  } catch (const Error& e) {
    if (e.file().empty()) throw ValueError(e.message(), file, line);
    throw;
  }
  p.settings = s.to_json();
  p.settings_text = p.settings.dump(0);
  return p;
}

uint64_t fnv1a(const std::string& bytes, uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace dp::experiments
