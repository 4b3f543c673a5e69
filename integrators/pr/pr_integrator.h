// `--integrator pr`: generalized path reusing in the primal domain (Bauszat et al. 2017,
// Sec. 3.1, Eq. 7). Iterations over jittered T x T reuse tiles (reuse_tiling.h); in each
// iteration every pixel gets one base walk and every base walk is reused in its tile
// (pr_tracer.h). `--spp N` runs N iterations, `--time S` iterations until the budget is
// used up (steady_clock); the first iteration always completes, later ones stop at tile
// boundaries (Ctrl-C or budget), and every pixel is normalised by its own count (an "spp"
// layer says which pixels have fewer). Random streams come from (seed, iteration, tile),
// so the image depends only on the seed, not on the thread count. Output: the image.
#pragma once

#include "integrators/integrator.h"
#include "integrators/pr/pr_settings.h"

namespace dp::integrators {

class PrIntegrator final : public Integrator {
 public:
  explicit PrIntegrator(Settings& settings) : m_settings(PrSettings::read(settings)), m_json(settings.to_json()) {}
  PrIntegrator(const PrSettings& settings, const core::Json& json) : m_settings(settings), m_json(json) {}
  std::string name() const override { return "pr"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // `render --partial`/`--mpi` (issue 17): part k of n runs the global iterations k, k + n, ...
  // (reuse_iterations.h), so the parts' summed buffers are the single render's.
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  PrSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
