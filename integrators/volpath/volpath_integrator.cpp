#include "integrators/volpath/volpath_integrator.h"

#include <algorithm>

#include "integrators/radiance_render.h"
#include "integrators/volpath/volpath_tracer.h"

namespace dp::integrators {

RenderResult VolpathIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width();
  const VolpathTracer tracer(scene, m_settings, options.max_depth);
  RenderResult result;
  if (!tracer.light_tracing()) {
    result = render_radiance(scene, options, "volpath", [&](const Tile& tile, int spp, core::Rng& rng,
                                                            std::vector<Rgbd>& sum, core::Stats& stats) {
      trace_tile<VolpathCounters>(tile, spp, rng, w, sum, stats, "volpath",
                                  [&](const Vec2& raster, Rgb& L, VolpathCounters& counters) {
                                    L = tracer.radiance(cam.generate_ray(raster), rng, counters);
                                    return is_finite(L);  // a non-finite sample is counted and dropped, never splatted
                                  });
    });
  } else {  // one light path per camera sample, joined to the camera and the camera path (volpath_light.cpp)
    result = render_radiance_with_splats(scene, options, "volpath", [&](const Tile& tile, int spp, core::Rng& rng,
                                                                        std::vector<Rgbd>& sum,
                                                                        std::vector<Splat>& splats, core::Stats& stats) {
      VolpathTracer::LightEnd light;
      trace_tile<VolpathCounters>(
          tile, spp, rng, w, sum, stats, "volpath", [&](const Vec2& raster, Rgb& L, VolpathCounters& counters) {
            Vec2 at;
            Rgb splat;
            const bool splatted =
                tracer.trace_light(rng, counters, light) && tracer.splat_light(light, rng, counters, at, splat);
            L = tracer.radiance(cam.generate_ray(raster), rng, counters, &light);
            if (!is_finite(L)) return false;  // dropped whole, its splat too
            if (splatted)
              splats.push_back({std::min(int(at.y()), cam.height() - 1) * w + std::min(int(at.x()), w - 1), splat});
            return true;
          });
    });
  }
  result.info["media"] = scene.caps().has_media;
  result.info["light_tracing"] = tracer.light_tracing();
  return result;
}

RenderResult VolpathIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
