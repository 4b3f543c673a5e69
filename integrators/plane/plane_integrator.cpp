#include "integrators/plane/plane_integrator.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "integrators/beam/beam_bvh.h"
#include "integrators/media_photons/media_photon_render.h"
#include "integrators/plane/plane_bvh.h"
#include "integrators/plane/plane_gather.h"
#include "integrators/plane/plane_pass.h"
#include "integrators/radiance_render.h"

namespace dp::integrators {

RenderResult PlaneIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  BeamBvh beam_bvh;
  PlaneBvh plane_bvh;
  BeamSettings beam_settings;  // Beam-Beam 3D, no fault
  beam_settings.radius_scale = m_settings.radius_scale;
  MediaLightPass pass;
  pass.prepare = [&](const PhotonTraceParams& params, float r, PhotonTraceCounters& pc, core::Stats& stats,
                     std::unique_ptr<MediumGather>& gather) {
    PlanePassCounters counters;
    if (!trace_plane_pass(scene, params, options.stop, r, m_settings.piece_scale,
                          m_settings.fault == PlaneFault::beams_after_scatter, pc, counters, beam_bvh, plane_bvh))
      return false;
    counters.flush(stats, "plane");
    gather = std::make_unique<PlaneGather>(scene, m_settings, beam_settings, beam_bvh, plane_bvh, r, params.paths);
    return true;
  };
  pass.release = [&] {
    beam_bvh.release();
    plane_bvh.release();
  };
  pass.names.queries = "queries";
  pass.names.gathered = "contributions";
  pass.names.depth_skipped = "depth_skipped";
  pass.names.candidates = "beam_candidates";
  pass.names.parallel = "plane_parallel";
  pass.names.planes = true;
  RenderResult r = render_media_passes(scene, options, "plane", m_settings, 3, pass);
  PlanePassCounters{}.flush(r.stats, "plane");  // present (0) also when no light pass ran
  r.info["kernel"] = "planes 0d + beams 3d";
  r.info["plane_piece_scale"] = m_settings.piece_scale;
  return r;
}

RenderResult PlaneIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
