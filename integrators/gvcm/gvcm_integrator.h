// `--integrator gvcm`: gradient-domain vertex connection and merging (Sun et al. 2017,
// Algorithm 1): VCM's iteration (integrators/photon_iterations.h: one light path per pixel,
// a photon grid, one camera path per pixel) with every connection and merge shifted to
// the four neighbours (gvcm_tracer.h). The merging radius is global per iteration (VCM's
// single eta = pi r^2 N): r_1 = radius_scale x the median pixel footprint at the first
// connectable camera vertex (kernel_footprint.h), r_i = r_1 i^((radius_alpha - 1) / 2).
// Output layers as `gpt`: "" (the reconstruction chosen by `reconstruction`, default L1),
// recon_l1, recon_l2, primal, dx, dy, direct (lights seen directly: never shifted).
#pragma once

#include "integrators/gvcm/gvcm_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GvcmIntegrator final : public Integrator {
 public:
  explicit GvcmIntegrator(Settings& settings) : m_settings(GvcmSettings::read(settings)), m_json(settings.to_json()) {}
  GvcmIntegrator(const GvcmSettings& settings, core::Json json) : m_settings(settings), m_json(std::move(json)) {}
  std::string name() const override { return "gvcm"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial / --mpi: iterations split between the parts (photon_iterations.h), raw
  // gradient buffers as gpt's.
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GvcmSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
