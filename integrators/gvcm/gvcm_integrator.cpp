#include "integrators/gvcm/gvcm_integrator.h"

#include <cmath>
#include <memory>

#include "core/timer.h"
#include "integrators/gvcm/gvcm_tracer.h"
#include "integrators/kernel_footprint.h"
#include "integrators/photon_iterations.h"

namespace dp::integrators {

RenderResult GvcmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int64_t pixels = int64_t(cam.width()) * cam.height();
  const int threads = resolve_threads(options);
  const double r0 = first_radius(scene, options.max_depth, m_settings.rr_depth, double(m_settings.radius_scale));
  VcmSettings light_settings;  // VCM's light pass: every vertex stored, photons listed
  light_settings.mode = m_settings.merging ? VcmMode::vcm : VcmMode::bpt;  // bpt: no photons listed
  light_settings.rr_depth = m_settings.rr_depth;
  std::vector<GvcmScratch> scratch(static_cast<size_t>(threads));
  core::Timer timer;
  const PhotonIterations run = render_photon_iterations(
      scene, options, "gvcm", light_settings,
      [&](int64_t i) {
        VcmIteration it;
        it.index = i;
        it.seed = options.seed;
        it.max_depth = options.max_depth;
        it.radius = float(r0 * std::pow(double(i + 1), 0.5 * (double(m_settings.radius_alpha) - 1.0)));
        it.light_tracing = false;  // light tracing per pixel in the camera pass (its shift needs the pixel)
        it.mis.heuristic = m_settings.heuristic;
        it.mis.min_merge_roughness = m_settings.roughness_threshold;
        it.mis.adaptive_kernel = m_settings.adaptive_kernel;
        it.mis.eta = m_settings.merging ? float(kPiD * double(it.radius) * double(it.radius) * double(pixels)) : 0.0f;
        return it;
      },
      [&](const VcmIteration& it, const LightPathStore& light, const PhotonGrid& grid) -> IterationTileFn {
        return pixel_tiles<GvcmCounters>(std::make_shared<const GvcmTracer>(scene, m_settings, it, light, grid),
                                         scratch);
      });

  RenderResult result = options.raw ? gradient_raw_result(run.passes, run.thread_stats)
                                    : gradient_result(run.passes, run.thread_stats, m_settings.alpha,
                                                      m_settings.reconstruction, options, m_json);
  result.stats.add("gvcm.iterations", run.passes.kept);
  result.stats.add("gvcm.light_paths", run.passes.kept * pixels);
  result.stats.add("gvcm.light_vertices", run.light.light_vertices);
  result.stats.add("gvcm.photons", run.photons);
  result.info["radius_initial"] = r0;
  result.info["radius_final"] = double(run.last_radius);
  result.wall_seconds = timer.seconds();
  return result;
}

RenderResult GvcmIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
