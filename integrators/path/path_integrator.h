// `--integrator path`: scheduling of the unidirectional path tracer over tiles. On a
// scene with participating media (Scene::caps().has_media) it delegates to `volpath`
// with the same settings (rr_depth, nee, hide_emitters): counters are then `volpath.*`
// and the sidecar's info says `delegated_to: volpath`.
#pragma once

#include "integrators/integrator.h"
#include "integrators/path/path_settings.h"

namespace dp::integrators {

class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(Settings& settings) : m_settings(PathSettings::read(settings)) {}
  std::string name() const override { return "path"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial: the raw sum "radiance" and count "spp"; finish() divides them per pixel.
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  PathSettings m_settings;
};

}  // namespace dp::integrators
