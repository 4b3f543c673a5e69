// What every primary-sample-space MCMC integrator (`mlt`, `gdmlt`) does around its target:
//  1. the bootstrap (mcmc/bootstrap.h): normalisation b and the pool of start states;
//  2. `chains` chains (seeded by (seed, chain index)), each started at a bootstrap sample
//     chosen with probability f_i / sum f (Veach 1997, Sec. 11.3.2), run in rounds by the
//     chain scheduler (chain_scheduler.h: images independent of the thread count);
//  3. expected-value splatting of every step (Veach 1997, Sec. 11.3.3): the current state
//     with weight 1 - a, the proposal with weight a, through the integrator's `splat`;
//  4. b refined by every large-step proposal (independent uniform samples, as the
//     bootstrap's; Kelemen et al. 2002), so the image scale converges with the render;
//  5. the shared counters ("<prefix>.mutations", acceptance, NaN drops, ...) and facts
//     (b, bootstrap time, chains, rounds) for the JSON sidecar.
// Image value of a buffer = scale() * splats, scale = b W H / mutations (the raster
// density on the image is 1 / (W H)).
// Parts (RenderOptions::part/parts, issue 17): every part runs the whole bootstrap (same
// seed: same b, same start states) and only its chains (chain_scheduler.h); norm() holds
// this part's share of b's samples and its mutations (mcmc_raw.h), so the parts' norms
// summed give the single render's b and scale.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/chain_scheduler.h"
#include "integrators/mcmc_raw.h"
#include "mcmc/bootstrap.h"
#include "mcmc/chain.h"

namespace dp::integrators {

struct McmcConfig {
  int64_t bootstrap = 100000;
  int chains = 0;  // 0 = 4 per thread
  bool large_step_b = true;
  mcmc::ChainOptions chain;
  int layers = 1;  // splat buffers of W H pixels
};

class McmcDriver {
 public:
  // splat(value, weight, out): a state's splats with its expected-value weight (> 0).
  using Splat = std::function<void(const mcmc::TargetValue& v, double weight, SplatList& out)>;
  // after(step, out): optional, once per step (e.g. a density count).
  using AfterStep = std::function<void(const mcmc::Step& s, SplatList& out)>;
  // after_round(rounds so far): optional, on the calling thread between rounds.
  using AfterRound = std::function<void(int64_t rounds)>;

  // Runs the bootstrap (one target per chain is made by `make`, plus the bootstrap's own).
  McmcDriver(const mcmc::TargetFactory& make, const McmcConfig& config, const scene::Scene& scene,
             const RenderOptions& options);
  // Runs the chains (--spp: spp W H mutations; --time: until options.time_budget).
  const ChainRunResult& run(const RenderOptions& options, const std::string& label, const Splat& splat,
                            const AfterStep& after = {}, const AfterRound& after_round = {});

  double b() const { return m_b; }          // refined normalisation of this part's samples (after run)
  const McmcNorm& norm() const { return m_norm; }  // this part's share (after run)
  double scale() const;                      // b W H / mutations
  int chains() const { return int(m_chains.size()); }
  // Chain c's target (another part's chain: an idle target shared by those chains).
  mcmc::Target& target(int c) { return m_targets[size_t(c)] ? *m_targets[size_t(c)] : *m_idle; }
  const ChainRunResult& result() const { return m_run; }
  // Counters "<prefix>.*" and info facts shared by the MCMC integrators.
  void report(RenderResult& result, const std::string& prefix) const;

 private:
  McmcConfig m_cfg;
  int64_t m_pixels;
  int m_width, m_height;
  std::unique_ptr<mcmc::Bootstrap> m_boot;
  double m_bootstrap_seconds = 0;
  std::vector<std::unique_ptr<mcmc::Target>> m_targets;  // null for another part's chain
  std::unique_ptr<mcmc::Target> m_idle;
  std::vector<mcmc::Chain> m_chains;  // safe to move (mcmc/chain.h)
  std::vector<mcmc::ChainCounters> m_counters;
  std::vector<int64_t> m_large;
  std::vector<double> m_large_f;
  ChainRunResult m_run;
  double m_b = 0;
  McmcNorm m_norm;
  mcmc::SampleShare m_share;  // this part's bootstrap samples
};

}  // namespace dp::integrators
