// `--integrator gpr`: gradient-domain path reusing (Bauszat et al. 2017, Sec. 3.2-3.3,
// Eq. 8). Iterations over jittered T x T tiles as `pr` (pr/reuse_iterations.h: `--spp N`
// = N iterations, `--time S` = iterations until the budget, tile granularity after the
// first; deterministic per seed, independent of the thread count); per tile the extended
// tile's base walks are reused for every pixel and forward gradient of its inner part
// (gpr_tracer.h). Output layers as `gpt` (gradient_output.h): "" (the reconstruction
// chosen by `reconstruction`, default L1), recon_l1, recon_l2, primal, direct, dx, dy.
// Every pixel and pair is normalised by the iterations that rendered its tile. Info:
// the paper's Table 1 (rr_skipped_percent, paths_per_pixel, paths_per_gradient and their
// share of the extended tile's base paths) and the iteration count.
#pragma once

#include "integrators/gpr/gpr_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GprIntegrator final : public Integrator {
 public:
  explicit GprIntegrator(Settings& settings) : m_settings(GprSettings::read(settings)), m_json(settings.to_json()) {}
  GprIntegrator(const GprSettings& settings, const core::Json& json) : m_settings(settings), m_json(json) {}
  std::string name() const override { return "gpr"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // `render --partial`/`--mpi` (issue 17): part k of n runs the global iterations k, k + n, ...
  // (reuse_iterations.h), so the parts' summed buffers are the single render's.
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GprSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
