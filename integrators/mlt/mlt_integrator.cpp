#include "integrators/mlt/mlt_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "integrators/mcmc_driver.h"
#include "integrators/mcmc_raw.h"
#include "integrators/mlt/mlt_path.h"
#include "mcmc/path_target.h"

namespace dp::integrators {

RenderResult MltIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  if (m_settings.path_space) {
    RenderResult result = render_mlt_path(scene, options, m_settings, m_name);
    result.info["settings"] = m_json;
    return result;
  }
  core::Timer timer;
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  pathspace::WalkOptions wo;
  wo.max_depth = options.max_depth;
  wo.rr_depth = m_settings.rr_depth;
  wo.nee = m_settings.nee;
  McmcConfig cfg;
  cfg.bootstrap = m_settings.bootstrap;
  cfg.chains = m_settings.chains;
  cfg.large_step_b = m_settings.large_step_b;
  cfg.chain.large_step_prob = m_settings.large_step_prob;
  cfg.chain.small_step = m_settings.small_step;
  McmcDriver driver([&] { return std::make_unique<mcmc::PathTarget>(scene, wo); }, cfg, scene, options);
  driver.run(options, "mlt", [&](const mcmc::TargetValue& v, double weight, SplatList& out) {
    const int px = std::clamp(int(v.raster.x()), 0, w - 1), py = std::clamp(int(v.raster.y()), 0, h - 1);
    out.add(0, int64_t(py) * w + px, v.value.cast<double>() * (weight / v.f));
  });

  core::RawImage raw = empty_raw(w, h);
  raw.sums["splat"] = driver.result().sums[0];
  driver.norm().write(raw);
  RenderResult result = options.raw ? RenderResult{} : finish(raw, finish_options(options));
  if (options.raw) result.raw = std::move(raw);
  driver.report(result, "mlt");
  if (!options.raw) fill_mcmc_counts(driver.norm(), int64_t(w) * h, finish_options(options), result);
  result.wall_seconds = timer.seconds();
  // Interrupted (Ctrl-C) is partial in both modes; a --time render that used its budget is not.
  result.partial = driver.result().partial;
  result.info["settings"] = m_json;
  return result;
}

RenderResult MltIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  if (m_settings.path_space) {
    RenderResult result = finish_mlt_path(raw, options, m_settings);
    result.info["settings"] = m_json;
    return result;
  }
  const McmcNorm norm = McmcNorm::read(raw);
  const int64_t pixels = int64_t(raw.width) * raw.height;
  const double scale = norm.scale(pixels);
  const std::vector<Rgbd>& sum = raw.sum("splat");
  core::Image img(raw.width, raw.height);
  for (size_t i = 0; i < sum.size(); ++i) img[i] = (sum[i] * scale).cast<float>();
  RenderResult result;
  result.layers.push_back({"", std::move(img)});
  fill_mcmc_counts(norm, pixels, options, result);
  result.info["settings"] = m_json;
  return result;
}

std::unique_ptr<Integrator> make_memlt(Settings& settings) {
  MltSettings defaults;
  defaults.path_space = true;
  defaults.path_mutations.preset = "memlt";
  const MltSettings m = MltSettings::read(settings, defaults);
  return std::make_unique<MltIntegrator>(m, settings.to_json(), "memlt");
}

}  // namespace dp::integrators
