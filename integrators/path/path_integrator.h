// `--integrator path`: scheduling of the unidirectional path tracer over tiles.
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
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  PathSettings m_settings;
};

}  // namespace dp::integrators
