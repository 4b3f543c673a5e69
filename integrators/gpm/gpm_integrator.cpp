#include "integrators/gpm/gpm_integrator.h"

#include <algorithm>
#include <cmath>

#include <memory>

#include "core/timer.h"
#include "integrators/gpm/gpm_tracer.h"
#include "integrators/kernel_footprint.h"
#include "integrators/photon_iterations.h"

namespace dp::integrators {


RenderResult GpmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int64_t pixels = int64_t(cam.width()) * cam.height();
  const int threads = resolve_threads(options);
  const double grid_r0 = first_radius(scene, options.max_depth, m_settings.rr_depth, double(m_settings.radius_scale));
  auto shrink = [&](int64_t i) { return std::pow(double(i + 1), 0.5 * (double(m_settings.radius_alpha) - 1.0)); };
  VcmSettings light_settings;  // the light pass of VCM's photon mapping: photons, no light tracing
  light_settings.mode = VcmMode::ppm;
  light_settings.rr_depth = m_settings.rr_depth;
  std::vector<GpmScratch> scratch(static_cast<size_t>(threads));
  core::Timer timer;
  double last_shrink = 1.0;
  const PhotonIterations run = render_photon_iterations(
      scene, options, "gpm", light_settings,
      [&](int64_t i) {
        VcmIteration it;
        it.index = i;
        it.seed = options.seed;
        it.max_depth = options.max_depth;
        it.radius = float(grid_r0 * shrink(i));  // the grid's cells; each query uses its own kernel
        return it;
      },
      [&](const VcmIteration& it, const LightPathStore& light, const PhotonGrid& grid) -> IterationTileFn {
        last_shrink = shrink(it.index);
        return pixel_tiles<GpmCounters>(
            std::make_shared<const GpmTracer>(scene, m_settings, options.max_depth,
                                              double(m_settings.radius_scale) * last_shrink, light, grid),
            scratch);
      });

  RenderResult result = options.raw ? gradient_raw_result(run.passes, run.thread_stats)
                                    : gradient_result(run.passes, run.thread_stats, m_settings.alpha,
                                                      m_settings.reconstruction, options, m_json);
  result.stats.add("gpm.iterations", run.passes.kept);
  result.stats.add("gpm.light_paths", run.passes.kept * pixels);
  result.stats.add("gpm.light_vertices", run.light.light_vertices);
  result.stats.add("gpm.photons", run.photons);
  result.info["radius_scale"] = double(m_settings.radius_scale);
  result.info["radius_grid_initial"] = grid_r0;  // the grid's cells: radius_scale x the median footprint
  result.info["radius_final_factor"] = double(m_settings.radius_scale) * last_shrink;
  result.wall_seconds = timer.seconds();
  return result;
}

RenderResult GpmIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
