#include "integrators/beam/beam_integrator.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "integrators/beam/beam_bvh.h"
#include "integrators/beam/beam_gather.h"
#include "integrators/media_photons/media_photon_render.h"
#include "integrators/radiance_render.h"

namespace dp::integrators {

RenderResult BeamIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  BeamBvh bvh;
  MediaLightPass pass;
  pass.prepare = [&](const PhotonTraceParams& params, float r, PhotonTraceCounters& pc, core::Stats& stats,
                     std::unique_ptr<MediumGather>& gather) {
    PhotonTraceParams tp = params;
    tp.store_photons = false;  // the same light paths as vpm's; only their beams are kept
    std::vector<MediumPhoton> none;
    std::vector<MediumBeam> beams;
    BeamTraceCounters bc;
    if (!trace_medium_photons(scene, tp, options.stop, none, pc, nullptr, &beams, &bc)) return false;
    stats.add("beam.beams_stored", bc.stored);
    stats.add("beam.beams_clipped", bc.clipped);
    stats.add("beam.beam_nan_dropped", bc.dropped);
    const float piece = beam_piece_length(scene, beams, r);
    bvh.build(std::move(beams), piece);
    stats.add("beam.beam_pieces", int64_t(bvh.pieces()));
    gather = std::make_unique<BeamGather>(scene, m_settings, bvh, r, tp.paths);
    return true;
  };
  pass.release = [&] { bvh.release(); };
  pass.names.queries = "queries";
  pass.names.gathered = "contributions";
  pass.names.depth_skipped = "beams_depth_skipped";
  pass.names.candidates = "beam_candidates";
  pass.names.parallel = "parallel_skipped";
  RenderResult r = render_media_passes(scene, options, "beam", m_settings, m_settings.kernel_dim(), pass);
  // Present (0) also when no light pass ran (no media, or no complete iteration).
  for (const char* k : {"beam.beams_stored", "beam.beams_clipped", "beam.beam_nan_dropped", "beam.beam_pieces"})
    r.stats.add(k, 0);
  r.info["kernel"] = m_settings.kernel_name();
  return r;
}

RenderResult BeamIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
