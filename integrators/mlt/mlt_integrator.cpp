#include "integrators/mlt/mlt_integrator.h"

#include <algorithm>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/tile_scheduler.h"
#include "mcmc/bootstrap.h"
#include "mcmc/chain.h"
#include "mcmc/path_target.h"

namespace dp::integrators {

namespace {
// One worker's share: its chains (c = worker, worker + workers, ...) and its buffer.
struct Worker {
  std::vector<std::unique_ptr<mcmc::PathTarget>> targets;
  std::vector<mcmc::Chain> chains;
  std::vector<int64_t> quota;  // mutations still to run per chain (fixed-spp renders)
  std::vector<Rgbd> sum;
  mcmc::ChainCounters counters;
  int64_t mutations = 0;
};
}  // namespace

RenderResult MltIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * int64_t(h);
  const int threads = resolve_threads(options);
  pathspace::WalkOptions wo;
  wo.max_depth = options.max_depth;
  wo.rr_depth = m_settings.rr_depth;
  wo.nee = m_settings.nee;
  const mcmc::TargetFactory make = [&] { return std::make_unique<mcmc::PathTarget>(scene, wo); };

  // Normalisation b = E[f] and the pool of start states (Kelemen et al. 2002, Sec. 4).
  const mcmc::Bootstrap boot(make, m_settings.bootstrap, options.seed, threads);
  const double bootstrap_seconds = timer.seconds();

  const int chains = m_settings.chains > 0 ? m_settings.chains : 4 * threads;
  const int workers = std::min(threads, chains);
  const bool timed = options.time_budget > 0;
  const int64_t total = timed ? 0 : int64_t(std::max(1, options.spp)) * pixels;
  const int64_t round = std::max<int64_t>(1, pixels / chains);  // ~1 mutation per pixel per round
  mcmc::ChainOptions copt;
  copt.large_step_prob = m_settings.large_step_prob;

  std::vector<Worker> work(static_cast<size_t>(workers));
  for (int c = 0; c < chains; ++c) {
    if (boot.select(0.5) < 0) break;  // f == 0 everywhere: a black image, no chain can start
    Worker& wk = work[size_t(c % workers)];
    wk.targets.push_back(std::make_unique<mcmc::PathTarget>(scene, wo));
    wk.chains.emplace_back(*wk.targets.back(), copt, options.seed, uint64_t(c));
    wk.quota.push_back(total / chains + (c < total % chains ? 1 : 0));
  }

  core::Progress progress("mlt", timed ? 1000 : std::max<int64_t>(1, total), options.quiet);
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  core::parallel_for(workers, workers, [&](int64_t item, int) {
    Worker& wk = work[size_t(item)];
    wk.sum.assign(size_t(pixels), Rgbd::Zero());
    for (size_t i = 0; i < wk.chains.size(); ++i) {
      // Start state: bootstrap sample i chosen with probability f_i / sum f (Veach 1997, 11.3.2).
      core::Rng pick(options.seed, core::mix64(0x57A7'0000'0000ull + uint64_t(item) + uint64_t(i) * uint64_t(workers)));
      wk.chains[i].start(boot.replay(*wk.targets[i], boot.select(pick.uniform_double())));
    }
    auto splat = [&](const mcmc::TargetValue& v, double weight) {
      if (!(weight > 0.0) || !(v.f > 0.0)) return;
      const int px = std::clamp(int(v.raster.x()), 0, w - 1), py = std::clamp(int(v.raster.y()), 0, h - 1);
      wk.sum[size_t(py) * size_t(w) + size_t(px)] += v.value.cast<double>() * (weight / v.f);
    };
    for (bool busy = true; busy && !should_stop();) {
      busy = false;
      for (size_t i = 0; i < wk.chains.size(); ++i) {
        const int64_t n = timed ? round : std::min(round, wk.quota[i]);
        for (int64_t m = 0; m < n; ++m) {
          // Expected-value splatting (Veach 1997, Sec. 11.3.3): x with 1 - a, y with a.
          const mcmc::Step s = wk.chains[i].step();
          splat(s.current, 1.0 - s.a);
          splat(s.proposed, s.a);
        }
        wk.mutations += n;
        if (!timed) {
          wk.quota[i] -= n;
          busy |= wk.quota[i] > 0;
          progress.advance(n);
        } else {
          busy = true;
          progress.set_fraction(timer.seconds() / options.time_budget);
        }
      }
    }
    for (const auto& ch : wk.chains) wk.counters.merge(ch.counters());
  });
  progress.finish();

  RenderResult result;
  int64_t mutations = 0;
  mcmc::ChainCounters counters;
  std::vector<Rgbd> sum(size_t(pixels), Rgbd::Zero());
  for (const Worker& wk : work) {  // in worker order: deterministic
    mutations += wk.mutations;
    counters.merge(wk.counters);
    if (wk.sum.empty()) continue;
    for (size_t p = 0; p < sum.size(); ++p) sum[p] += wk.sum[p];
  }
  // Pixel j = W H * b * E_{f/b}[h_j C / f] ~ b / (mutations per pixel) * splats_j.
  const double scale = mutations > 0 ? boot.b() * double(pixels) / double(mutations) : 0.0;
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] * scale).cast<float>();
  result.layers.push_back({"", std::move(img)});

  result.stats.add("mlt.mutations", mutations);
  result.stats.add("mlt.large_steps", counters.large);
  result.stats.add("mlt.small_steps", counters.small);
  result.stats.add("mlt.accepted_large", counters.accepted_large);
  result.stats.add("mlt.accepted_small", counters.accepted_small);
  result.stats.add("mlt.zero_proposals", counters.zero);
  result.stats.add("mlt.nan_dropped", counters.invalid + boot.invalid());
  result.stats.add("mlt.bootstrap_samples", boot.samples());
  result.wall_seconds = timer.seconds();
  result.min_spp = result.max_spp = mutations / pixels;  // mutations per pixel (on average)
  result.partial = !timed && mutations < total;
  result.info["bootstrap_b"] = boot.b();
  result.info["bootstrap_seconds"] = bootstrap_seconds;
  result.info["acceptance_rate"] = counters.acceptance_rate();
  int started = 0;
  for (const Worker& wk : work) started += int(wk.chains.size());
  result.info["chains"] = started;
  result.info["mutations_per_pixel"] = double(mutations) / double(pixels);
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
