#include "integrators/gdmlt/gdmlt_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "gradients/shift_factory.h"
#include "integrators/gradient_output.h"
#include "integrators/mcmc_driver.h"
#include "integrators/gdmlt/direct_pass.h"
#include "integrators/tile_scheduler.h"
#include "mcmc/gradient_target.h"

namespace dp::integrators {

namespace {
enum Layer { kPrimal = 0, kDx = 1, kDy = 2, kDensity = 3, kLayers = 4 };

}  // namespace

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
  DirectPass direct(scene, m_settings, options);
  direct.render(m_settings.direct_spp > 0 ? m_settings.direct_spp : 1);

  gradients::ShiftChoice choice;
  choice.kind = m_settings.shift;
  choice.threshold = m_settings.shift_threshold;
  choice.fault = m_settings.fault;
  const std::unique_ptr<gradients::Shift> shift = gradients::make_shift(scene, choice);
  mcmc::GradientTargetOptions to;
  to.walk = pathspace::WalkOptions{options.max_depth, m_settings.rr_depth, m_settings.nee, m_settings.shift_threshold};
  to.alpha = m_settings.alpha;
  to.gradient = {m_settings.mwgi, m_settings.mwgi_threshold};

  // Bootstrap over the unit cube of (u_j, raster, path), then the chains.
  McmcConfig cfg;
  cfg.bootstrap = m_settings.bootstrap;
  cfg.chains = m_settings.chains;
  cfg.large_step_b = m_settings.large_step_b;
  cfg.chain.large_step_prob = m_settings.large_step_prob;
  cfg.chain.redraw_first = 1;  // the neighbour coordinate (gradient_target.h)
  cfg.layers = kLayers;
  McmcDriver driver([&] { return std::make_unique<mcmc::GradientTarget>(scene, *shift, to); }, cfg, scene, options);
  RenderOptions chain_opt = options;
  if (options.time_budget > 0) chain_opt.time_budget = std::max(1e-3, options.time_budget - timer.seconds());
  auto pixel_of = [&](const Vec2& r) {
    return int64_t(std::clamp(int(r.y()), 0, h - 1)) * w + std::clamp(int(r.x()), 0, w - 1);
  };
  const ChainRunResult& run = driver.run(
      chain_opt, "gdmlt",
      [&](const mcmc::TargetValue& v, double weight, SplatList& out) {
        const double k = weight / v.f;
        if (!is_black(v.value)) out.add(kPrimal, pixel_of(v.raster), v.value.cast<double>() * k);
        if (v.gradient_row >= 0 && !is_black(v.gradient)) {
          const bool dy = v.gradient_row >= pixels;
          out.add(dy ? kDy : kDx, dy ? v.gradient_row - pixels : v.gradient_row, v.gradient.cast<double>() * k);
        }
      },
      [&](const mcmc::Step& s, SplatList& out) {  // the paper's Fig. 9: mutations per pixel
        out.add(kDensity, pixel_of((s.accepted ? s.proposed : s.current).raster), Rgbd::Ones());
      },
      [&](int64_t rounds) {
        if (m_settings.direct_spp == 0) direct.render(int(rounds - direct.spp_done()));
      });

  mcmc::GradientTargetCounters target_sum;
  for (int c = 0; c < driver.chains(); ++c)  // in chain order: deterministic
    target_sum.merge(static_cast<mcmc::GradientTarget&>(driver.target(c)).counters());
  const double scale = driver.scale();
  auto image_of = [&](int layer, double k) {
    core::Image img(w, h);
    const std::vector<Rgbd>& sum = run.sums[size_t(layer)];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] * k).cast<float>();
    return img;
  };
  // Screened Poisson reconstruction of the indirect image (Manzi 2014, Eq. 8), then the
  // direct pass added (Sec. 4).
  add_gradient_layers(image_of(kPrimal, scale), image_of(kDx, scale), image_of(kDy, scale), direct.image(),
                      m_settings.alpha, m_settings.reconstruction, resolve_threads(options), result);
  const int64_t mutations = run.total_mutations;
  result.layers.push_back({"density", image_of(kDensity, mutations > 0 ? double(pixels) / double(mutations) : 0.0)});

  driver.report(result, "gdmlt");
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
  result.partial = run.partial || direct.partial();
  result.info["direct_spp"] = direct.spp_done();
  result.info["settings"] = m_json;
  return result;
}

}  // namespace dp::integrators
