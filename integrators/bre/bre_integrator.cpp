#include "integrators/bre/bre_integrator.h"

#include "integrators/bre/bre_gather.h"
#include "integrators/media_photons/media_photon_render.h"
#include "integrators/radiance_render.h"

namespace dp::integrators {

RenderResult BreIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  return render_media_photons(scene, options, "bre", m_settings, m_settings.kernel_dim,
                              [&](const PhotonBvh& photons, float radius, int64_t paths) {
                                return std::make_unique<BreGather>(scene, m_settings, photons, radius, paths);
                              });
}

RenderResult BreIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
