#include "integrators/gdmlt/gdmlt_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "gradients/shift_factory.h"
#include "integrators/chain_scheduler.h"
#include "integrators/path/path_tracer.h"
#include "integrators/tile_scheduler.h"
#include "mcmc/bootstrap.h"
#include "mcmc/chain.h"
#include "mcmc/gradient_target.h"
#include "reconstruct/solve.h"

namespace dp::integrators {

namespace {
enum Layer { kPrimal = 0, kDx = 1, kDy = 2, kDensity = 3, kLayers = 4 };

// Paths of at most 2 segments (emitters seen directly and direct lighting of the first
// hit) by the reference path tracer: the part of the image the chain does not sample.
core::Image render_direct(const scene::Scene& scene, const GdmltSettings& s, const RenderOptions& options,
                          core::Stats& stats, ScheduleResult& sched) {
  const int w = scene.camera().width(), h = scene.camera().height();
  PathSettings ps;
  ps.rr_depth = s.rr_depth;
  ps.nee = s.nee;
  const PathTracer tracer(scene, ps, std::min(2, options.max_depth));
  RenderOptions o = options;
  // direct_spp = 0 (auto): as many samples per pixel as mutations per pixel (--spp), or
  // direct_fraction of the budget (--time). A direct path costs far less than a mutation.
  const bool timed = options.time_budget > 0 && s.direct_spp == 0;
  o.time_budget = timed ? s.direct_fraction * options.time_budget : 0;
  o.spp = s.direct_spp > 0 ? s.direct_spp : std::max(1, options.spp);
  o.quiet = true;
  o.seed = core::mix64(options.seed ^ 0xD1EC'7000'0000'0001ull);
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero());
  std::vector<int64_t> dropped(size_t(resolve_threads(o)), 0);
  sched = run_tiles(w, h, o, "gdmlt direct", [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
    PathCounters counters;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        for (int i = 0; i < spp; ++i) {
          const Vec2 raster(float(x) + rng.uniform(), float(y) + rng.uniform());
          const Rgb L = tracer.radiance(scene.camera().generate_ray(raster), rng, counters);
          if (is_finite(L)) sum[size_t(y) * size_t(w) + size_t(x)] += L.cast<double>();
          else ++dropped[size_t(thread)];
        }
  });
  int64_t nan = 0;
  for (int64_t d : dropped) nan += d;
  stats.add("gdmlt.direct.nan_dropped", nan);
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int64_t n = sched.spp_at(x, y);
      if (n > 0) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] / double(n)).cast<float>();
    }
  return img;
}
}  // namespace

RenderResult GdmltIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * int64_t(h);
  const int threads = resolve_threads(options);
  RenderResult result;

  ScheduleResult direct_sched;
  core::Image direct = render_direct(scene, m_settings, options, result.stats, direct_sched);
  const double direct_seconds = timer.seconds();

  gradients::ShiftChoice choice;
  choice.kind = m_settings.shift;
  choice.threshold = m_settings.shift_threshold;
  choice.fault = m_settings.fault;
  const std::unique_ptr<gradients::Shift> shift = gradients::make_shift(scene, choice);
  mcmc::GradientTargetOptions to;
  to.walk = pathspace::WalkOptions{options.max_depth, m_settings.rr_depth, m_settings.nee, m_settings.shift_threshold};
  to.alpha = m_settings.alpha;
  to.gradient = {m_settings.mwgi, m_settings.mwgi_threshold};
  const mcmc::TargetFactory make = [&] { return std::make_unique<mcmc::GradientTarget>(scene, *shift, to); };

  // Normalisation b = E[f] over the unit cube of (u_j, raster, path) and the start states.
  const mcmc::Bootstrap boot(make, m_settings.bootstrap, options.seed, threads);
  const double bootstrap_seconds = timer.seconds() - direct_seconds;

  ChainSchedule sc;
  sc.chains = boot.select(0.5) < 0 ? 0 : (m_settings.chains > 0 ? m_settings.chains : 4 * threads);
  sc.total = options.time_budget > 0 ? 0 : int64_t(std::max(1, options.spp)) * pixels;
  sc.round = std::max<int64_t>(1, pixels / std::max(1, sc.chains));
  sc.layers = kLayers;
  sc.pixels = pixels;
  mcmc::ChainOptions copt;
  copt.large_step_prob = m_settings.large_step_prob;
  copt.redraw_first = 1;  // the neighbour coordinate (gradient_target.h)

  std::vector<std::unique_ptr<mcmc::GradientTarget>> targets;
  std::vector<mcmc::Chain> chains;
  for (int c = 0; c < sc.chains; ++c) {
    targets.push_back(std::make_unique<mcmc::GradientTarget>(scene, *shift, to));
    chains.emplace_back(*targets.back(), copt, options.seed, uint64_t(c));
  }
  std::vector<char> started(size_t(sc.chains), 0);
  std::vector<mcmc::ChainCounters> counters(size_t(sc.chains));
  std::vector<int64_t> large(size_t(sc.chains), 0);
  std::vector<double> large_f(size_t(sc.chains), 0.0);

  RenderOptions chain_opt = options;
  if (options.time_budget > 0) chain_opt.time_budget = std::max(1e-3, options.time_budget - timer.seconds());
  const ChainRunResult run = run_chains(sc, chain_opt, "gdmlt", [&](int c, int64_t n, SplatList& out, int) {
    mcmc::Chain& chain = chains[size_t(c)];
    if (!started[size_t(c)]) {
      // Start state: bootstrap sample chosen with probability f_i / sum f (Veach 1997, 11.3.2).
      core::Rng pick(options.seed, core::mix64(0x57A7'0000'0000ull + uint64_t(c)));
      chain.start(boot.replay(*targets[size_t(c)], boot.select(pick.uniform_double())));
      started[size_t(c)] = 1;
    }
    auto splat = [&](const mcmc::TargetValue& v, double weight) {
      if (!(weight > 0.0) || !(v.f > 0.0)) return;
      const int px = std::clamp(int(v.raster.x()), 0, w - 1), py = std::clamp(int(v.raster.y()), 0, h - 1);
      const double k = weight / v.f;
      if (!is_black(v.value)) out.add(kPrimal, int64_t(py) * w + px, v.value.cast<double>() * k);
      if (v.gradient_row >= 0 && !is_black(v.gradient)) {
        const bool dy = v.gradient_row >= pixels;
        out.add(dy ? kDy : kDx, dy ? v.gradient_row - pixels : v.gradient_row, v.gradient.cast<double>() * k);
      }
    };
    for (int64_t m = 0; m < n; ++m) {
      // Expected-value splatting (Veach 1997, Sec. 11.3.3): x with 1 - a, y with a.
      const mcmc::Step s = chain.step();
      if (s.large) {
        ++large[size_t(c)];
        if (s.proposed.valid()) large_f[size_t(c)] += std::max(0.0, s.proposed.f);
      }
      splat(s.current, 1.0 - s.a);
      splat(s.proposed, s.a);
      const mcmc::TargetValue& now = s.accepted ? s.proposed : s.current;  // the paper's Fig. 9 density
      out.add(kDensity, int64_t(std::clamp(int(now.raster.y()), 0, h - 1)) * w + std::clamp(int(now.raster.x()), 0, w - 1),
              Rgbd::Ones());
    }
    counters[size_t(c)] = chain.counters();
  });

  const int64_t mutations = run.total_mutations;
  int64_t large_steps = 0;
  double large_sum = 0;
  mcmc::ChainCounters chain_sum;
  mcmc::GradientTargetCounters target_sum;
  for (int c = 0; c < sc.chains; ++c) {  // in chain order: deterministic
    large_steps += large[size_t(c)];
    large_sum += large_f[size_t(c)];
    chain_sum.merge(counters[size_t(c)]);
    target_sum.merge(targets[size_t(c)]->counters());
  }
  // b from the bootstrap and every large step (both independent uniform samples; mlt).
  const double b = m_settings.large_step_b
                       ? (boot.b() * double(boot.samples()) + large_sum) / double(boot.samples() + large_steps)
                       : boot.b();
  // Every buffer is an integral over the cube with raster density 1 / (W H):
  // value = W H * b / mutations * splats (as mlt).
  const double scale = mutations > 0 ? b * double(pixels) / double(mutations) : 0.0;
  auto image_of = [&](int layer, double k) {
    core::Image img(w, h);
    const std::vector<Rgbd>& sum = run.sums[size_t(layer)];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] * k).cast<float>();
    return img;
  };
  const core::Image primal = image_of(kPrimal, scale), dx = image_of(kDx, scale), dy = image_of(kDy, scale);
  const core::Image density = image_of(kDensity, mutations > 0 ? double(pixels) / double(mutations) : 0.0);

  // Screened Poisson reconstruction of the indirect image (Manzi 2014, Eq. 8), then the
  // direct pass added (Sec. 4).
  const reconstruct::Problem problem = reconstruct::make_grid_problem(primal, dx, dy, m_settings.alpha);
  reconstruct::SolveOptions sopt;
  sopt.threads = threads;
  core::Timer solve_timer;
  core::Image l2 = reconstruct::solve_l2(problem, sopt).image;
  const double l2_seconds = solve_timer.seconds();
  solve_timer.reset();
  core::Image l1 = reconstruct::solve_l1(problem, sopt).image;
  const double l1_seconds = solve_timer.seconds();
  l2 += direct;
  l1 += direct;
  core::Image primal_full = primal;
  primal_full += direct;

  result.layers.push_back({"", m_settings.reconstruction == "l2" ? l2 : l1});
  result.layers.push_back({"recon_l1", std::move(l1)});
  result.layers.push_back({"recon_l2", std::move(l2)});
  result.layers.push_back({"primal", std::move(primal_full)});
  result.layers.push_back({"direct", std::move(direct)});
  result.layers.push_back({"dx", dx});
  result.layers.push_back({"dy", dy});
  result.layers.push_back({"density", density});

  result.stats.add("gdmlt.mutations", mutations);
  result.stats.add("gdmlt.large_steps", chain_sum.large);
  result.stats.add("gdmlt.small_steps", chain_sum.small);
  result.stats.add("gdmlt.accepted_large", chain_sum.accepted_large);
  result.stats.add("gdmlt.accepted_small", chain_sum.accepted_small);
  result.stats.add("gdmlt.zero_proposals", chain_sum.zero);
  result.stats.add("gdmlt.nan_dropped", chain_sum.invalid + boot.invalid());
  result.stats.add("gdmlt.bootstrap_samples", boot.samples());
  // Concrete paths by case of Eqs. 4-6: T_1 used (weight w_1), T_0 by Eq. 6, Omega_bar.
  result.stats.add("gdmlt.paths.shifted_t1", target_sum.cases[size_t(gradients::GradientCase::shifted)]);
  result.stats.add("gdmlt.paths.fallback_t0", target_sum.cases[size_t(gradients::GradientCase::fallback)]);
  result.stats.add("gdmlt.paths.omega_bar", target_sum.cases[size_t(gradients::GradientCase::omega_bar)]);
  result.stats.add("gdmlt.shift.attempted", target_sum.shifts);
  for (int i = 0; i < gradients::kShiftStatusCount; ++i)
    result.stats.add(std::string("gdmlt.shift.") + gradients::to_string(gradients::ShiftStatus(i)),
                     target_sum.shift_status[size_t(i)]);
  if (target_sum.walks.attempted > 0) target_sum.walks.flush(result.stats, "gdmlt.manifold");
  result.stats.add("gdmlt.manifold.walks", target_sum.walks.attempted);

  result.wall_seconds = timer.seconds();
  result.min_spp = result.max_spp = mutations / pixels;
  result.partial = run.partial || direct_sched.partial;
  result.info["bootstrap_b"] = boot.b();
  result.info["b"] = b;
  result.info["direct_seconds"] = direct_seconds;
  result.info["bootstrap_seconds"] = bootstrap_seconds;
  result.info["chain_seconds"] = run.seconds;
  result.info["solve_l2_seconds"] = l2_seconds;
  result.info["solve_l1_seconds"] = l1_seconds;
  result.info["acceptance_rate"] = chain_sum.acceptance_rate();
  result.info["chains"] = sc.chains;
  result.info["rounds"] = run.rounds;
  result.info["mutations_per_pixel"] = double(mutations) / double(pixels);
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
