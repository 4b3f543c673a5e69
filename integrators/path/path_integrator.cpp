#include "integrators/path/path_integrator.h"

#include "integrators/path/path_tracer.h"
#include "integrators/radiance_render.h"
#include "integrators/volpath/volpath_integrator.h"

namespace dp::integrators {

RenderResult PathIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  if (scene.caps().has_media) {
    // Media are rendered by volpath (issue 15), with this integrator's settings; the
    // counters are volpath's and the sidecar says so.
    VolpathIntegrator volpath(VolpathSettings::from_path(m_settings));
    RenderResult result = volpath.render(scene, options);
    result.info["delegated_to"] = "volpath";
    return result;
  }
  const auto& cam = scene.camera();
  const int w = cam.width();
  const PathTracer tracer(scene, m_settings, options.max_depth);
  return render_radiance(scene, options, "path", [&](const Tile& tile, int spp, core::Rng& rng, std::vector<Rgbd>& sum,
                                                     core::Stats& stats) {
    trace_tile<PathCounters>(tile, spp, rng, w, sum, stats, "pt", [&](const Vec2& raster, Rgb& L, PathCounters& counters) {
      L = tracer.radiance(cam.generate_ray(raster), rng, counters);
      return is_finite(L);  // a non-finite sample is counted and dropped, never splatted
    });
  });
}

RenderResult PathIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
