// `--integrator bre`: the progressive beam radiance estimate (Jarosz et al. 2008; the
// primal BRE of Gruson et al. 2018, Sec. 5.1): photons as `vpm`'s
// (media_photons/photon_tracer.h), camera paths as volpath on surfaces, and one beam
// query per camera segment inside a medium (bre_gather.h) with a 2D uniform kernel whose
// radius shrinks per iteration, r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1)
// (media_photons/volume_kernel.h). `--spp` = iterations, `--time` whole iterations.
// Counters `bre.*`; info: media, radius_initial, radius_final, kernel_dimension.
#pragma once

#include "integrators/bre/bre_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class BreIntegrator final : public Integrator {
 public:
  explicit BreIntegrator(Settings& settings) : m_settings(BreSettings::read(settings)) {}
  explicit BreIntegrator(const BreSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "bre"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }  // photons by delta tracking, Tr by ratio tracking
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  BreSettings m_settings;
};

}  // namespace dp::integrators
