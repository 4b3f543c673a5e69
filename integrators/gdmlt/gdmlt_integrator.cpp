#include "integrators/gdmlt/gdmlt_integrator.h"

#include <algorithm>

#include "core/rng.h"
#include "core/timer.h"
#include "gradients/ao_map.h"
#include "gradients/shift_factory.h"
#include "gradients/symmetric_gradient.h"
#include "integrators/direct_pass.h"
#include "integrators/gdmlt/gdmlt_path.h"
#include "integrators/gdmlt/gdmlt_raw.h"
#include "integrators/gradient_output.h"
#include "integrators/mcmc_driver.h"
#include "integrators/tile_scheduler.h"
#include "kernels_adaptive/features.h"
#include "kernels_adaptive/kernel_problem.h"
#include "kernels_adaptive/pair_kernel.h"
#include "mcmc/gradient_target.h"
#include "reconstruct/pair_layers.h"

namespace dp::integrators {

namespace {
constexpr int kPrimal = kGdmltPrimal, kDensity = kGdmltDensity, kRows = kGdmltRows;  // gdmlt_path.h

// The primary-sample-space chains (McmcDriver over mcmc::GradientTarget).
void run_pss_chains(const scene::Scene& scene, const GdmltSettings& st, const RenderOptions& options,
                    const RenderOptions& chain_opt, const gradients::ShiftChoice& choice,
                    const kernels_adaptive::PairKernel& kernel, int layers, DirectPass& direct, RenderResult& result,
                    ChainRunResult& run, McmcNorm& norm, mcmc::GradientTargetCounters& target_sum) {
  core::Timer timer;
  const int w = scene.camera().width(), h = scene.camera().height();
  const int64_t pixels = int64_t(w) * int64_t(h);
  const std::unique_ptr<gradients::Shift> shift = gradients::make_shift(scene, choice);
  mcmc::GradientTargetOptions to;
  to.walk = pathspace::WalkOptions{options.max_depth, st.rr_depth, st.nee, st.shift_threshold};
  to.alpha = st.alpha;
  to.gradient = {st.mwgi, st.mwgi_threshold};
  // Bootstrap over the unit cube of (u_j, raster, path), then the chains.
  McmcConfig cfg;
  cfg.bootstrap = st.bootstrap;
  cfg.chains = st.chains;
  cfg.large_step_b = st.large_step_b;
  cfg.chain.large_step_prob = st.large_step_prob;
  cfg.chain.redraw_first = 1;  // the neighbour coordinate (gradient_target.h)
  cfg.layers = layers;
  McmcDriver driver([&] { return std::make_unique<mcmc::GradientTarget>(scene, *shift, kernel, to); }, cfg, scene,
                    options);
  auto pixel_of = [&](const Vec2& r) {
    return int64_t(std::clamp(int(r.y()), 0, h - 1)) * w + std::clamp(int(r.x()), 0, w - 1);
  };
  RenderOptions budget = chain_opt;  // the bootstrap used part of it
  if (chain_opt.time_budget > 0) budget.time_budget = std::max(1e-3, chain_opt.time_budget - timer.seconds());
  run = driver.run(
      budget, "gdmlt",
      [&](const mcmc::TargetValue& v, double weight, SplatList& out) {
        const double k = weight / v.f;
        if (!is_black(v.value)) out.add(kPrimal, pixel_of(v.raster), v.value.cast<double>() * k);
        if (v.gradient_row >= 0 && !is_black(v.gradient))
          out.add(kRows + int(v.gradient_row / pixels), v.gradient_row % pixels, v.gradient.cast<double>() * k);
      },
      [&](const mcmc::Step& s, SplatList& out) {  // the paper's Fig. 9: mutations per pixel
        out.add(kDensity, pixel_of((s.accepted ? s.proposed : s.current).raster), Rgbd::Ones());
      },
      [&](int64_t rounds) {
        if (st.direct_spp == 0) direct.render(int(rounds - direct.spp_done()));
      });
  for (int c = 0; c < driver.chains(); ++c)  // in chain order: deterministic
    target_sum.merge(static_cast<mcmc::GradientTarget&>(driver.target(c)).counters());
  norm = driver.norm();
  driver.report(result, "gdmlt");
}
}  // namespace

RenderResult GdmltIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  RenderResult result;
  add_gdmlt_layers(raw, options, m_settings, result);
  result.info["settings"] = m_json;
  return result;
}

RenderResult GdmltIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * int64_t(h);
  RenderResult result;

  // Direct light: all of it first when direct_spp is given; else (auto) one sample per
  // pixel now and, after every round of the chains (about one mutation per pixel), as
  // many as the rounds so far: direct spp tracks mutations per pixel, and an interrupted
  // render has both parts.
  PathSettings direct_settings;
  direct_settings.rr_depth = m_settings.rr_depth;
  direct_settings.nee = m_settings.nee;
  DirectPass direct(scene, direct_settings, options, "gdmlt direct");
  direct.render(m_settings.direct_spp > 0 ? m_settings.direct_spp : 1);

  // The pair kernel: the 4-neighbour forward differences, or the structure-adaptive pairs
  // from a feature pass (Manzi 2014, Sec. 3.5; only then is the feature pass run). Every
  // part runs the same feature pass (same seed), so all parts use one kernel.
  kernels_adaptive::Features features;
  double feature_seconds = 0;
  if (m_settings.kernel == "adaptive") {
    core::Timer ft;
    features = kernels_adaptive::render_features(scene, m_settings.feature_spp,
                                                 core::mix64(options.seed ^ 0xFEA7'0000'0000'0001ull),
                                                 resolve_threads(options));
    feature_seconds = ft.seconds();
  }
  const kernels_adaptive::PairKernel kernel = gdmlt_kernel(m_settings, features, w, h);
  const int64_t rows = int64_t(kernel.rows.size());
  const int row_buffers = int((rows + pixels - 1) / pixels);

  gradients::ShiftChoice choice;
  choice.kind = m_settings.shift;
  choice.threshold = m_settings.shift_threshold;
  choice.fault = m_settings.fault;
  // INCMW: the screen-space AO map first (only then), the symmetric decision from it.
  std::unique_ptr<gradients::AoMap> ao;
  double ao_seconds = 0;
  const bool path_space = m_settings.mutations == "path";
  if (m_settings.incmw && m_settings.shift != "identity" && !path_space) {
    core::Timer at;
    gradients::AoMapSettings as;
    as.radius = float(m_settings.ao_radius);
    as.rays = m_settings.ao_rays;
    as.seed = core::mix64(options.seed ^ 0xA0A0'0000'0000'0001ull);
    as.threads = resolve_threads(options);
    ao = std::make_unique<gradients::AoMap>(scene, as);
    const gradients::AoMap* map = ao.get();
    choice.incremental =
        gradients::symmetric_threshold([map](const Vec3& p) { return map->lookup(p); }, float(m_settings.ao_threshold));
    ao_seconds = at.seconds();
  }
  const int layers = kRows + row_buffers;
  RenderOptions chain_opt = options;
  if (options.time_budget > 0) chain_opt.time_budget = std::max(1e-3, options.time_budget - timer.seconds());
  ChainRunResult run;
  McmcNorm norm;
  mcmc::GradientTargetCounters target_sum;
  if (path_space) {
    GdmltChains chains = run_gdmlt_path(scene, chain_opt, m_settings, kernel, layers, direct, result);
    run = std::move(chains.run);
    norm = chains.norm;
    target_sum = chains.target;
  } else {
    run_pss_chains(scene, m_settings, options, chain_opt, choice, kernel, layers, direct, result, run, norm, target_sum);
  }
  // A part whose chains needed fewer rounds than the whole render's makes the direct
  // passes the single render made after those rounds (--spp; a --time part keeps its own).
  if (m_settings.direct_spp == 0 && options.time_budget <= 0 && !run.interrupted) {
    ChainSchedule whole;
    whole.chains = int(run.mutations.size());
    whole.total = int64_t(std::max(1, options.spp)) * pixels;
    whole.round = std::max<int64_t>(1, pixels / std::max(1, whole.chains));
    direct.catch_up(whole_rounds(whole));
  }

  core::RawImage raw = gdmlt_raw(run, norm, features, ao.get(), m_settings, options, w, h);
  direct.write(raw);
  // The layers: the code a merge of parts runs (one Poisson reconstruction).
  if (options.raw) {
    result.raw = std::move(raw);
    fill_part_counts(run.total_mutations, pixels, result);
  } else {
    add_gdmlt_layers(raw, finish_options(options), m_settings, result);
  }
  if (m_settings.kernel == "adaptive") result.info["feature_seconds"] = feature_seconds;
  if (ao) result.info["ao_seconds"] = ao_seconds;
  int64_t symmetric = 0;
  for (const auto& e : kernel.entries) symmetric += e.weight == 2.0f;
  // What ran and what was skipped: the passes' rays (0 = not run), INCMW's declarations.
  // Every part runs the feature and AO passes and builds the kernel (same seed, same
  // result): part 1 reports them, so the counters of the parts sum to the single render's.
  const bool first = options.part == 0;
  result.stats.add("gdmlt.features.rays",
                   first && m_settings.kernel == "adaptive" ? pixels * m_settings.feature_spp : 0);
  result.stats.add("gdmlt.ao.rays", first && ao ? pixels * m_settings.ao_rays : 0);
  result.stats.add("gdmlt.incmw.shifts", target_sum.incmw_shifts);
  result.stats.add("gdmlt.incmw.declared_vertices", target_sum.incmw_declared);
  result.stats.add("gdmlt.kernel.rows", first ? rows : 0);
  result.stats.add("gdmlt.kernel.symmetric_entries", first ? symmetric : 0);
  result.stats.add("gdmlt.kernel.entries", first ? int64_t(kernel.entries.size()) : 0);

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
  result.stats.add("gdmlt.direct.nan_dropped", direct.nan_dropped());
  result.partial = result.partial || run.partial || direct.partial();  // or an interrupted reconstruction
  result.info["direct_spp"] = direct.spp_done();
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
