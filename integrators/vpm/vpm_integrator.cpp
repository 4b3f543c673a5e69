#include "integrators/vpm/vpm_integrator.h"

#include "integrators/media_photons/media_photon_render.h"
#include "integrators/radiance_render.h"
#include "integrators/vpm/vpm_gather.h"

namespace dp::integrators {

RenderResult VpmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  RenderResult r = render_media_photons(scene, options, "vpm", m_settings, 3,
                                        [&](const PhotonBvh& photons, float radius, int64_t paths) {
                                          return std::make_unique<VpmGather>(scene, m_settings, photons, radius, paths);
                                        });
  r.info["distance_samples"] = m_settings.distance_samples;
  return r;
}

RenderResult VpmIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
