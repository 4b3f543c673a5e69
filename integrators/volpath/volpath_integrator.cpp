#include "integrators/volpath/volpath_integrator.h"

#include "integrators/radiance_render.h"
#include "integrators/volpath/volpath_tracer.h"

namespace dp::integrators {

RenderResult VolpathIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width();
  const VolpathTracer tracer(scene, m_settings, options.max_depth);
  RenderResult result = render_radiance(scene, options, "volpath", [&](const Tile& tile, int spp, core::Rng& rng,
                                                                       std::vector<Rgbd>& sum, core::Stats& stats) {
    VolpathCounters counters;
    const int64_t dropped = accumulate_tile(tile, spp, rng, w, sum, [&](const Vec2& raster, Rgb& L) {
      L = tracer.radiance(cam.generate_ray(raster), rng, counters);
      return is_finite(L);  // a non-finite sample is counted and dropped, never splatted
    });
    counters.flush(stats);
    stats.add("volpath.paths", int64_t(spp) * (tile.x1 - tile.x0) * (tile.y1 - tile.y0));
    stats.add("volpath.nan_dropped", dropped);
  });
  result.info["media"] = scene.caps().has_media;
  return result;
}

RenderResult VolpathIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
