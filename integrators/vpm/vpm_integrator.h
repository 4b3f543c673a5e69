// `--integrator vpm`: progressive volumetric photon mapping (Jensen & Christensen 1998;
// the primal estimator of Gruson et al. 2018, Sec. 4): photons stored at the medium
// scattering events of light paths (media_photons/photon_tracer.h), camera paths as
// volpath on surfaces and a point-point estimate along every camera segment inside a
// medium (vpm_gather.h), with a 3D uniform kernel whose radius shrinks per iteration,
// r_{i+1}^3 = r_i^3 (i + alpha) / (i + 1) (media_photons/volume_kernel.h). `--spp` =
// iterations, `--time` whole iterations (media_photons/media_photon_render.h). Counters
// `vpm.*`; info: media, radius_initial, radius_final, kernel_dimension.
#pragma once

#include "integrators/integrator.h"
#include "integrators/vpm/vpm_settings.h"

namespace dp::integrators {

class VpmIntegrator final : public Integrator {
 public:
  explicit VpmIntegrator(Settings& settings) : m_settings(VpmSettings::read(settings)) {}
  explicit VpmIntegrator(const VpmSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "vpm"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }  // photons by delta tracking, Tr by ratio tracking
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  VpmSettings m_settings;
};

}  // namespace dp::integrators
