// `--integrator gdmlt`: gradient-domain Metropolis light transport on the extended path
// space (Manzi et al. 2014, Sec. 4; Lehtinen et al. 2013). Scheduling:
//  1. direct light: the reference path tracer restricted to paths of at most 2 segments
//     (integrators/direct_pass.h), interleaved with the chains' rounds, added after reconstruction;
//  2. bootstrap of the extended-path-space target (mcmc/gradient_target.h): b and the
//     chains' start states;
//  3. `chains` primary-sample-space chains in rounds (chain_scheduler.h), the neighbour
//     coordinate redrawn at every mutation, expected-value splatting of the primal and of
//     the pair gradient into dx/dy (and one density count per mutation);
//  4. screened Poisson reconstruction (L1 and L2) of the indirect image, plus the direct.
// --spp N = N mutations per pixel on average; --time includes the direct light and the
// bootstrap. Deterministic for a seed and chain count, whatever the thread count.
// `--partial` / `--mpi` (issue 17): raw buffers and finish() in gdmlt_raw.h; finish()
// runs the reconstruction once on the merged buffers (primal, rows, direct).
#pragma once

#include "integrators/gdmlt/gdmlt_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GdmltIntegrator final : public Integrator {
 public:
  explicit GdmltIntegrator(Settings& settings)
      : m_settings(GdmltSettings::read(settings)), m_json(settings.to_json()) {}
  // Settings given in code (tests: members that are not --set keys).
  GdmltIntegrator(const GdmltSettings& settings, core::Json json) : m_settings(settings), m_json(std::move(json)) {}
  std::string name() const override { return "gdmlt"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GdmltSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
