// `--integrator volpath`: the volumetric path tracer (volpath_tracer.h) scheduled over
// tiles as `path` (radiance_render.h), with `--partial` raw buffers. Counters
// `volpath.*`; info `media` says whether the scene had any.
#pragma once

#include "integrators/integrator.h"
#include "integrators/volpath/volpath_settings.h"

namespace dp::integrators {

class VolpathIntegrator final : public Integrator {
 public:
  explicit VolpathIntegrator(Settings& settings) : m_settings(VolpathSettings::read(settings)) {}
  explicit VolpathIntegrator(const VolpathSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "volpath"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  VolpathSettings m_settings;
};

}  // namespace dp::integrators
