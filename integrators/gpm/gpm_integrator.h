// `--integrator gpm`: gradient-domain photon mapping as Sun et al. 2017 (Sec. 7) implement
// G-PM: VCM's iteration (one light path per pixel, a photon grid, one camera path per
// pixel; integrators/vcm) with merging only at the first connectable camera vertex z_b,
// each merge shifted to the four neighbours (gpm_tracer.h). The kernel radius follows each
// camera path's pixel footprint at z_b (x radius_scale) and shrinks per iteration,
// r_i = r_1 i^((radius_alpha - 1) / 2). `--spp` = iterations; `--time` runs whole
// iterations; an interrupted iteration is discarded. Output layers as `gpt`: "" (the
// reconstruction chosen by `reconstruction`, default L1), recon_l1, recon_l2, primal,
// dx, dy, direct (emission through Dirac-only prefixes and merges at mixed vertices before
// z_b: never shifted, added to both reconstructions).
#pragma once

#include "integrators/gpm/gpm_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GpmIntegrator final : public Integrator {
 public:
  explicit GpmIntegrator(Settings& settings) : m_settings(GpmSettings::read(settings)), m_json(settings.to_json()) {}
  GpmIntegrator(const GpmSettings& settings, core::Json json) : m_settings(settings), m_json(std::move(json)) {}
  std::string name() const override { return "gpm"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial / --mpi: iterations split between the parts (photon_iterations.h), raw
  // gradient buffers as gpt's.
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GpmSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
