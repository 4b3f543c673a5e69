#include "integrators/mlt/mlt_path.h"

#include <algorithm>

#include "core/error.h"
#include "core/timer.h"
#include "integrators/chain_scheduler.h"
#include "integrators/direct_pass.h"
#include "integrators/mcmc_raw.h"
#include "integrators/path_chains.h"
#include "integrators/tile_scheduler.h"
#include "mcmc/path_json.h"

namespace dp::integrators {

namespace {

// replay=CHAIN:STEP: the chain's path after STEP steps and the last step, as JSON.
RenderResult replay_chain(const scene::Scene& scene, const RenderOptions& options, const MltSettings& settings,
                          const std::string& name, const mcmc::PathSeeder& seeder,
                          const std::vector<mcmc::WeightedMutator>& mutators, const core::Timer& timer) {
  RenderResult result;
  result.layers.push_back({"", core::Image(scene.camera().width(), scene.camera().height())});
  core::Json j = core::Json::object();
  j["chain"] = settings.replay_chain;
  j["step"] = double(settings.replay_step);
  if (!(seeder.b() > 0.0)) {
    j["error"] = "no light reaches the camera (b = 0): no chain starts";
    result.info["replay"] = j;
    return result;
  }
  mcmc::PathState x;
  start_path(seeder, options.seed, settings.replay_chain, name, x);
  mcmc::PathChain chain(mutators, options.seed, uint64_t(settings.replay_chain));
  chain.start(x);
  j["start"] = mcmc::path_state_json(chain.current());
  mcmc::PathStep last;
  for (int64_t i = 0; i < settings.replay_step; ++i) last = chain.step();
  j["state"] = mcmc::path_state_json(chain.current());
  if (settings.replay_step > 0) {
    core::Json l = core::Json::object();
    l["mutation"] = last.mutator >= 0 ? mutators[size_t(last.mutator)].mutator->name() : "none";
    l["outcome"] = mcmc::proposal_status_name(last.status);
    l["a"] = last.a;
    l["accepted"] = last.accepted;
    j["last_step"] = l;
  }
  j["b"] = seeder.b();
  result.info["replay"] = j;
  result.info["state_space"] = "path";
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace

RenderResult render_mlt_path(const scene::Scene& scene, const RenderOptions& options, const MltSettings& settings,
                             const std::string& name) {
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * h;

  // Direct light (<= 2 segments) by the path tracer, the chains the rest (Mitsuba 0.6).
  const bool direct = settings.direct_spp >= 0 && settings.replay_chain < 0;
  const mcmc::PathSeedOptions so = seed_options(options, settings.rr_depth, settings.bootstrap, direct ? 3 : 1);
  const mcmc::PathSeeder seeder(scene, so);
  const double bootstrap_seconds = timer.seconds();

  const PathMutatorSet set(scene, settings.path_mutations, so.min_depth, options.max_depth, settings.path_fault);
  const std::vector<mcmc::WeightedMutator>& mutators = set.list();
  const int n_chains = seeder.b() > 0.0 ? resolve_chains(settings.chains, options) : 0;
  ChainSchedule sc;
  sc.chains = n_chains;
  sc.total = options.time_budget > 0 ? 0 : int64_t(std::max(1, options.spp)) * pixels;
  sc.round = std::max<int64_t>(1, pixels / std::max(1, sc.chains));
  sc.pixels = pixels;
  sc.part = options.part;
  sc.parts = options.parts;
  std::vector<mcmc::PathChain> chains;
  int64_t seed_retries = 0;
  {
    mcmc::PathState x;
    for (int c = 0; c < n_chains; ++c) {
      chains.emplace_back(mutators, options.seed, uint64_t(c));
      if (!owns_chain(sc, c)) continue;  // another part's (its start depends on c alone)
      seed_retries += start_path(seeder, options.seed, c, name, x);
      chains.back().start(x);
    }
  }

  if (settings.replay_chain >= 0) return replay_chain(scene, options, settings, name, seeder, mutators, timer);

  std::unique_ptr<DirectPass> direct_pass;
  if (direct) {
    PathSettings ps;
    ps.rr_depth = settings.rr_depth;
    direct_pass = std::make_unique<DirectPass>(scene, ps, options, name + " direct");
    direct_pass->render(settings.direct_spp > 0 ? settings.direct_spp : 1);
  }

  // Auto: after every round (about one mutation per pixel) the direct pass catches up to
  // as many samples per pixel as rounds, so an interrupted render has both parts.
  if (direct_pass && settings.direct_spp == 0)
    sc.after_round = [&](int64_t rounds) { direct_pass->render(int(rounds - direct_pass->spp_done())); };
  std::vector<mcmc::PathChainCounters> counters(static_cast<size_t>(n_chains));
  auto splat = [&](const mcmc::PathSplat& p, double weight, SplatList& out) {
    const int px = std::clamp(int(p.raster.x()), 0, w - 1), py = std::clamp(int(p.raster.y()), 0, h - 1);
    out.add(0, int64_t(py) * w + px, p.colour.cast<double>() * weight);
  };
  // --time is the whole render's budget: the seeding and the direct pass used part of it
  // (the chains still run at least one round).
  RenderOptions chain_options = options;
  if (options.time_budget > 0) chain_options.time_budget = std::max(1e-3, options.time_budget - timer.seconds());
  const ChainRunResult run = run_chains(sc, chain_options, name, [&](int c, int64_t n, SplatList& out, int) {
    mcmc::PathChain& chain = chains[size_t(c)];
    for (int64_t m = 0; m < n; ++m) {
      const mcmc::PathStep st = chain.step();
      // Expected-value splatting (Veach 1997, Sec. 11.3.3): x with 1 - a, y with a.
      if (st.a < 1.0) splat(st.current, 1.0 - st.a, out);
      if (st.a > 0.0) splat(st.proposed, st.a, out);
    }
    counters[size_t(c)] = chain.counters();
  });

  // A part whose chains needed fewer rounds than the whole render's makes the direct
  // passes the single render made after those rounds (--spp; a --time part keeps its own).
  if (direct_pass && settings.direct_spp == 0 && options.time_budget <= 0 && !run.interrupted)
    direct_pass->catch_up(whole_rounds(sc));

  const mcmc::SampleShare share = seeder.share(options.part, options.parts);
  McmcNorm norm;
  norm.b.sum = share.sum;
  norm.b.n = share.n;
  norm.mutations = run.total_mutations;
  core::RawImage raw = empty_raw(w, h);
  raw.sums["splat"] = run.sums[0];
  norm.write(raw);
  if (direct_pass) direct_pass->write(raw);
  RenderResult result = options.raw ? RenderResult{} : finish_mlt_path(raw, finish_options(options), settings);
  if (options.raw) {
    result.raw = std::move(raw);
    fill_part_counts(run.total_mutations, pixels, result);
  }

  mcmc::PathChainCounters sum;
  for (const auto& c : counters) sum.merge(c);  // chain order
  result.stats.add(name + ".mutations", run.total_mutations);
  const int64_t invalid = report_path_chains(result, name, mutators, sum);
  result.stats.add(name + ".path.seed_retries", seed_retries);
  // Shares (the seeder's samples, this part's direct units and chains), so the counters of
  // the parts of a render sum to the single render's; the direct spp every part makes is
  // part 1's to report.
  result.stats.add(name + ".nan_dropped",
                   share.invalid + invalid + (direct_pass ? direct_pass->nan_dropped() : 0));
  result.stats.add(name + ".direct_spp", direct_pass && options.part == 0 ? direct_pass->spp_done() : 0);
  result.stats.add(name + ".bootstrap_samples", share.n);
  result.info["state_space"] = "path";
  result.info["bootstrap_b"] = seeder.b();
  result.info["bootstrap_seconds"] = bootstrap_seconds;
  result.info["chain_seconds"] = run.seconds;
  result.info["chains"] = n_chains;
  result.info["rounds"] = run.rounds;
  result.wall_seconds = timer.seconds();
  result.partial = run.partial || (direct_pass && direct_pass->partial());
  return result;
}

RenderResult finish_mlt_path(const core::RawImage& raw, const RenderOptions& options, const MltSettings& settings) {
  const McmcNorm norm = McmcNorm::read(raw);
  const int64_t pixels = int64_t(raw.width) * raw.height;
  const double scale = norm.scale(pixels);
  const std::vector<Rgbd>& sum = raw.sum("splat");
  core::Image img(raw.width, raw.height);
  for (size_t i = 0; i < sum.size(); ++i) img[i] = (sum[i] * scale).cast<float>();
  if (settings.direct_spp >= 0) {  // the direct pass's paths (<= 2 segments)
    const core::Image d = DirectPass::image(raw);
    for (size_t i = 0; i < sum.size(); ++i) img[i] += d[i];
  }
  RenderResult result;
  result.layers.push_back({"", std::move(img)});
  fill_mcmc_counts(norm, pixels, options, result);
  return result;
}

}  // namespace dp::integrators
