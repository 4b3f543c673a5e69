#include "integrators/mcmc_driver.h"

#include <algorithm>

#include "core/timer.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

McmcDriver::McmcDriver(const mcmc::TargetFactory& make, const McmcConfig& config, const scene::Scene& scene,
                       const RenderOptions& options)
    : m_cfg(config),
      m_pixels(int64_t(scene.camera().width()) * scene.camera().height()),
      m_width(scene.camera().width()),
      m_height(scene.camera().height()) {
  core::Timer timer;
  const int threads = resolve_threads(options);
  m_boot = std::make_unique<mcmc::Bootstrap>(make, m_cfg.bootstrap, options.seed, threads);
  m_bootstrap_seconds = timer.seconds();
  m_b = m_boot->b();
  // f == 0 everywhere: a black image, no chain can start.
  const int chains = m_boot->select(0.5) < 0 ? 0 : resolve_chains(m_cfg.chains, options);
  // Another part's chains never step here: they share one idle target (never evaluated,
  // its counters stay 0) instead of a target each.
  for (int c = 0; c < chains; ++c) {
    const bool own = owns_chain(c, options.part, options.parts);
    if (!own && !m_idle) m_idle = make();
    m_targets.push_back(own ? make() : nullptr);
    m_chains.emplace_back(own ? *m_targets.back() : *m_idle, m_cfg.chain, options.seed, uint64_t(c));
  }
  m_counters.resize(size_t(chains));
  m_large.assign(size_t(chains), 0);
  m_large_f.assign(size_t(chains), 0.0);
}

const ChainRunResult& McmcDriver::run(const RenderOptions& options, const std::string& label, const Splat& splat,
                                      const AfterStep& after, const AfterRound& after_round) {
  ChainSchedule sc;
  sc.chains = chains();
  sc.total = options.time_budget > 0 ? 0 : int64_t(std::max(1, options.spp)) * m_pixels;
  sc.round = std::max<int64_t>(1, m_pixels / std::max(1, sc.chains));  // ~1 mutation per pixel per round
  sc.layers = m_cfg.layers;
  sc.pixels = m_pixels;
  sc.part = options.part;
  sc.parts = options.parts;
  sc.after_round = after_round;
  std::vector<char> started(size_t(sc.chains), 0);
  m_run = run_chains(sc, options, label, [&](int c, int64_t n, SplatList& out, int) {
    mcmc::Chain& chain = m_chains[size_t(c)];
    if (!started[size_t(c)]) {
      // Start state: bootstrap sample i chosen with probability f_i / sum f (Veach 1997, 11.3.2).
      core::Rng pick(options.seed, core::mix64(0x57A7'0000'0000ull + uint64_t(c)));
      chain.start(m_boot->replay(*m_targets[size_t(c)], m_boot->select(pick.uniform_double())));
      started[size_t(c)] = 1;
    }
    for (int64_t m = 0; m < n; ++m) {
      const mcmc::Step s = chain.step();
      if (s.large) {
        ++m_large[size_t(c)];
        if (s.proposed.valid()) m_large_f[size_t(c)] += std::max(0.0, s.proposed.f);
      }
      // Expected-value splatting (Veach 1997, Sec. 11.3.3): x with 1 - a, y with a.
      if (s.a < 1.0 && s.current.f > 0.0) splat(s.current, 1.0 - s.a, out);
      if (s.a > 0.0 && s.proposed.f > 0.0) splat(s.proposed, s.a, out);
      if (after) after(s, out);
    }
    m_counters[size_t(c)] = chain.counters();
  });
  // b = E[f] over uniform primary samples: the bootstrap's and every large step's
  // proposal are such samples, so their mean is unbiased and its error falls with the
  // render (Kelemen et al. 2002). This part's share: its bootstrap samples, its chains'
  // large steps (mcmc_raw.h).
  m_share = m_boot->share(options.part, options.parts);
  m_norm = McmcNorm{};
  m_norm.b.sum = m_share.sum;
  m_norm.b.n = m_share.n;
  if (m_cfg.large_step_b)
    for (int c = 0; c < sc.chains; ++c) m_norm.b.n += m_large[size_t(c)], m_norm.b.sum += m_large_f[size_t(c)];  // chain order
  m_norm.mutations = m_run.total_mutations;
  m_b = m_norm.value();
  return m_run;
}

double McmcDriver::scale() const { return m_norm.scale(m_pixels); }

void McmcDriver::report(RenderResult& result, const std::string& prefix) const {
  mcmc::ChainCounters sum;
  for (const auto& c : m_counters) sum.merge(c);
  const int64_t mutations = m_run.total_mutations;
  result.stats.add(prefix + ".mutations", mutations);
  result.stats.add(prefix + ".large_steps", sum.large);
  result.stats.add(prefix + ".small_steps", sum.small);
  result.stats.add(prefix + ".accepted_large", sum.accepted_large);
  result.stats.add(prefix + ".accepted_small", sum.accepted_small);
  result.stats.add(prefix + ".zero_proposals", sum.zero);
  // The bootstrap's share: the parts' counters sum to the whole render's.
  result.stats.add(prefix + ".nan_dropped", sum.invalid + m_share.invalid);
  result.stats.add(prefix + ".bootstrap_samples", m_share.n);
  fill_part_counts(mutations, m_pixels, result);  // mutations per pixel (on average)
  result.info["bootstrap_b"] = m_boot->b();
  result.info["b"] = m_b;
  result.info["bootstrap_seconds"] = m_bootstrap_seconds;
  result.info["chain_seconds"] = m_run.seconds;
  result.info["acceptance_rate"] = sum.acceptance_rate();
  result.info["chains"] = chains();
  result.info["rounds"] = m_run.rounds;
  result.info["mutations_per_pixel"] = double(mutations) / double(m_pixels);
}

}  // namespace dp::integrators
