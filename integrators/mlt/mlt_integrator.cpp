#include "integrators/mlt/mlt_integrator.h"

#include <algorithm>

#include "core/timer.h"
#include "integrators/mcmc_driver.h"
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

  RenderResult result;
  const double scale = driver.scale();
  core::Image img(w, h);
  const std::vector<Rgbd>& sum = driver.result().sums[0];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img(x, y) = (sum[size_t(y) * size_t(w) + size_t(x)] * scale).cast<float>();
  result.layers.push_back({"", std::move(img)});
  driver.report(result, "mlt");
  result.wall_seconds = timer.seconds();
  // Interrupted (Ctrl-C) is partial in both modes; a --time render that used its budget is not.
  result.partial = driver.result().partial;
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
