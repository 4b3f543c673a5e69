#include "integrators/gdmlt/gdmlt_path.h"

#include <algorithm>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/path_chains.h"
#include "integrators/tile_scheduler.h"
#include "mcmc/path_gradient.h"

namespace dp::integrators {

namespace {

struct Candidate {
  mcmc::PathState x;
  double factor = 0;  // 0: not usable (no path, or a non-finite target)
};

// Candidate k: a seeder path (its own stream) and its own u_pair, with its factor.
void draw_candidate(const mcmc::PathSeeder& seeder, uint64_t seed, int k, mcmc::PathGradientFactor& factor,
                    Candidate& out) {
  core::Rng rng(seed, core::mix64(0xCA4D'0000'0000ull + uint64_t(k)));
  mcmc::PathSides sides;
  out.factor = 0.0;
  if (!seeder.select(rng.uniform_double(), out.x, sides)) return;
  out.x.u_pair = rng.uniform_double();
  factor.evaluate(out.x);
  if (std::isfinite(out.x.factor) && out.x.factor > 0.0) out.factor = out.x.factor;
}

}  // namespace

GdmltChains run_gdmlt_path(const scene::Scene& scene, const RenderOptions& options, const GdmltSettings& settings,
                           const kernels_adaptive::PairKernel& kernel, int layers, DirectPass& direct,
                           RenderResult& result) {
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * h;
  const int threads = resolve_threads(options);

  // Paths of <= 2 segments are the direct pass's.
  const mcmc::PathSeedOptions so = seed_options(options, settings.rr_depth, settings.bootstrap, 3);
  const mcmc::PathSeeder seeder(scene, so);

  mcmc::PathGradientOptions po;
  po.alpha = settings.alpha;
  po.gradient = {settings.mwgi, settings.mwgi_threshold};
  po.shift.fault = settings.fault;
  po.shift.walk_chains = settings.shift == "manifold";
  po.identity = settings.shift == "identity";
  const PathMutatorSet set(scene, settings.path_mutations, so.min_depth, options.max_depth);
  const std::vector<mcmc::WeightedMutator>& mutators = set.list();

  // b_g = b E[factor] and the start states (header), in parallel blocks, deterministic.
  const int n_chains = seeder.b() > 0.0 ? resolve_chains(settings.chains, options) : 0;
  const int n_cand = seeder.b() > 0.0 ? std::max(settings.candidates, 4 * n_chains) : 0;
  const uint64_t cand_seed = core::mix64(options.seed ^ 0x6D17'0000'0000'0001ull);
  std::vector<Candidate> cand(static_cast<size_t>(n_cand));
  core::parallel_for((n_cand + 255) / 256, threads, [&](int64_t block, int) {
    mcmc::PathGradientFactor factor(scene, kernel, po);
    for (int k = int(block) * 256; k < std::min(n_cand, int(block + 1) * 256); ++k)
      draw_candidate(seeder, cand_seed, k, factor, cand[size_t(k)]);
  });
  std::vector<double> cdf(cand.size());
  double total = 0.0;
  for (size_t k = 0; k < cand.size(); ++k) cdf[k] = total += cand[k].factor;
  const double b_g = n_cand > 0 ? seeder.b() * total / double(n_cand) : 0.0;

  ChainSchedule sc;
  sc.part = options.part;
  sc.parts = options.parts;
  std::vector<mcmc::PathChain> chains;
  if (total > 0.0)
    for (int c = 0; c < n_chains; ++c) {
      core::Rng pick(options.seed, core::mix64(0x57A7'0000'0000ull + uint64_t(c)));
      const auto it = std::upper_bound(cdf.begin(), cdf.end(), pick.uniform_double() * total);
      size_t k = size_t(std::min<std::ptrdiff_t>(it - cdf.begin(), std::ptrdiff_t(cdf.size()) - 1));
      while (k > 0 && !(cand[k].factor > 0.0)) --k;  // round-off past the last usable one
      if (!owns_chain(sc, c)) {  // another part's chain never steps here: no target
        chains.emplace_back(mutators, options.seed, uint64_t(c));
        continue;
      }
      chains.emplace_back(mutators, options.seed, uint64_t(c),
                          std::make_unique<mcmc::PathGradientFactor>(scene, kernel, po));
      chains.back().start(cand[k].x);
    }
  const double seed_seconds = timer.seconds();

  if (settings.direct_spp == 0) sc.after_round = [&](int64_t rounds) { direct.render(int(rounds - direct.spp_done())); };
  sc.chains = int(chains.size());
  sc.total = options.time_budget > 0 ? 0 : int64_t(std::max(1, options.spp)) * pixels;
  sc.round = std::max<int64_t>(1, pixels / std::max(1, sc.chains));
  sc.layers = layers;
  sc.pixels = pixels;
  auto pixel_of = [&](const Vec2& r) {
    return int64_t(std::clamp(int(r.y()), 0, h - 1)) * w + std::clamp(int(r.x()), 0, w - 1);
  };
  auto splat = [&](const mcmc::PathSplat& p, double weight, SplatList& out) {
    const double k = weight / p.factor;
    out.add(kGdmltPrimal, pixel_of(p.raster), p.colour.cast<double>() * k);
    if (p.pair_row >= 0 && !is_black(p.pair))
      out.add(kGdmltRows + int(p.pair_row / pixels), p.pair_row % pixels, p.pair.cast<double>() * k);
  };
  std::vector<mcmc::PathChainCounters> counters(chains.size());
  RenderOptions chain_options = options;
  if (options.time_budget > 0) chain_options.time_budget = std::max(1e-3, options.time_budget - timer.seconds());
  GdmltChains out;
  out.run = run_chains(sc, chain_options, "gdmlt", [&](int c, int64_t n, SplatList& list, int) {
    mcmc::PathChain& chain = chains[size_t(c)];
    for (int64_t m = 0; m < n; ++m) {
      const mcmc::PathStep st = chain.step();
      if (st.a < 1.0) splat(st.current, 1.0 - st.a, list);
      if (st.a > 0.0) splat(st.proposed, st.a, list);
      list.add(kGdmltDensity, pixel_of((st.accepted ? st.proposed : st.current).raster), Rgbd::Ones());
    }
    counters[size_t(c)] = chain.counters();
  });
  // b_g = b E[factor]: this part's shares of both means (mcmc_raw.h).
  const mcmc::SampleShare share = seeder.share(options.part, options.parts);
  out.norm.b.sum = share.sum;
  out.norm.b.n = share.n;
  int64_t own_cand = 0, unusable = 0;
  for (int k = 0; k < n_cand; ++k)  // index order
    if (mcmc::owns_sample(k, mcmc::PathSeeder::kBlock, options.part, options.parts)) {
      out.norm.factor.sum += cand[size_t(k)].factor;
      ++out.norm.factor.n;
      ++own_cand;
      unusable += !(cand[size_t(k)].factor > 0.0);
    }
  out.norm.mutations = out.run.total_mutations;

  mcmc::PathChainCounters sum;
  int64_t lt_only = 0;
  for (size_t c = 0; c < chains.size(); ++c) {  // chain order: deterministic
    sum.merge(counters[c]);
    if (!chains[c].factor()) continue;  // another part's chain
    const auto& f = static_cast<const mcmc::PathGradientFactor&>(*chains[c].factor());
    out.target.merge(f.counters());
    lt_only += f.light_tracing_only();
  }
  const int64_t invalid = report_path_chains(result, "gdmlt", mutators, sum);
  result.stats.add("gdmlt.mutations", out.run.total_mutations);
  // Shares of the seeder's samples and of the candidates: parts' counters sum to the whole's.
  result.stats.add("gdmlt.nan_dropped", share.invalid + invalid);
  result.stats.add("gdmlt.bootstrap_samples", share.n);
  result.stats.add("gdmlt.path.seed_candidates", own_cand);
  result.stats.add("gdmlt.path.seed_candidates_unusable", unusable);
  result.stats.add("gdmlt.path.light_tracing_only", lt_only);  // states in Omega_bar by construction
  result.info["state_space"] = "path";
  result.info["bootstrap_b"] = seeder.b();
  result.info["b_g"] = b_g;
  result.info["bootstrap_seconds"] = seed_seconds;
  result.info["chain_seconds"] = out.run.seconds;
  result.info["chains"] = int(chains.size());
  result.info["rounds"] = out.run.rounds;
  return out;
}

}  // namespace dp::integrators
