// `--integrator gbdpt`: gradient-domain bidirectional path tracing (Manzi et al. 2015)
// over tiles, in whole passes (integrators/gradient_passes.h). Output layers as `gpt`:
// "" (RGB: the reconstruction chosen by `reconstruction`, default L1), recon_l1,
// recon_l2, primal (BDPT primal + direct), dx, dy (forward differences, direct light
// excluded) and direct (paths of one segment: never shifted, kept out of the Poisson
// solve and added to both reconstructions).
#pragma once

#include "integrators/gbdpt/gbdpt_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GbdptIntegrator final : public Integrator {
 public:
  explicit GbdptIntegrator(Settings& settings)
      : m_settings(GbdptSettings::read(settings)), m_json(settings.to_json()) {}
  std::string name() const override { return "gbdpt"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial / --mpi: the raw primal, dx, dy and direct sums and counts (gradient_passes.h).
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GbdptSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
