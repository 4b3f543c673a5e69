// `--integrator mlt`: primary-sample-space Metropolis light transport (Kelemen et al.
// 2002, as Mitsuba's PSSMLT) on top of mcmc/. Scheduling: a bootstrap of independent
// paths gives the normalisation b and the start states; `chains` independent chains
// (seeded by (seed, chain index)) run in rounds (chain_scheduler.h), so the image is
// deterministic for a given seed and chain count, whatever the thread count (the
// default chain count, 4 per thread, does depend on it). --spp N means N
// mutations per pixel on average (N W H in total); --time runs rounds of mutations until
// the wall-clock budget is used. Image: b / (mutations per pixel) * splats, with
// expected-value splatting of the current and the proposed state (Veach 1997, 11.3.3).
// `--partial` / `--mpi` (issue 17): part k of n runs chains c = k (mod n) of the same
// chain set with the same streams; raw buffers "splat" and the normalisation of
// integrators/mcmc_raw.h (plus the direct pass's "direct" in path space); finish() turns
// them -- one render's or the sum of the parts' -- into the image, so a render's image is
// always made by the code a merge runs.
#pragma once

#include "integrators/integrator.h"
#include "integrators/mlt/mlt_settings.h"

namespace dp::integrators {

class MltIntegrator final : public Integrator {
 public:
  explicit MltIntegrator(Settings& settings) : m_settings(MltSettings::read(settings)), m_json(settings.to_json()) {}
  // Settings given in code (tests: members that are not --set keys).
  MltIntegrator(const MltSettings& settings, core::Json json, std::string name = "mlt")
      : m_settings(settings), m_json(std::move(json)), m_name(std::move(name)) {}
  std::string name() const override { return m_name; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return m_settings.replay_chain < 0; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  MltSettings m_settings;
  core::Json m_json;
  std::string m_name = "mlt";
};

// `--integrator memlt`: manifold exploration Metropolis light transport (Jakob & Marschner
// 2012): `mlt` with mutations=path and the mutation set memlt (bidirectional, lens,
// caustic and manifold); counters "memlt.*".
std::unique_ptr<Integrator> make_memlt(Settings& settings);

}  // namespace dp::integrators
