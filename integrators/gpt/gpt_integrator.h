// `--integrator gpt`: gradient-domain path tracing (Kettunen et al. 2015) over tiles; in
// scenes with homogeneous media the shift copies medium distances and reconnects at medium
// vertices (gpt_media_tracer.h; Gruson et al. 2018, Sec. 6).
// Renders whole passes (every pixel the same sample count, which the symmetric pair
// estimates need); a time budget runs 1-spp passes until it is used up. Output layers:
// "" (RGB: the reconstruction chosen by `reconstruction`, default L1), recon_l1, recon_l2,
// primal (MIS-weighted primal + direct), dx, dy (forward differences, direct light
// excluded) and direct (emitters seen directly from the camera: never shifted, kept out
// of the Poisson solve and added to both reconstructions). `--partial` writes the sums
// and counts of primal, dx, dy and direct before any reconstruction; finish() runs it.
#pragma once

#include "integrators/gpt/gpt_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GptIntegrator final : public Integrator {
 public:
  explicit GptIntegrator(Settings& settings) : m_settings(GptSettings::read(settings)), m_json(settings.to_json()) {}
  std::string name() const override { return "gpt"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  // Homogeneous media through GptMediaTracer (gpt_media_tracer.h); grid media are refused.
  bool renders_media() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GptSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
