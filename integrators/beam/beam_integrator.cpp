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
    // Pieces of at most max(16 r, diag / 128) (beam_bvh.h), longer if that would make more
    // than 8M pieces (memory: ~15 bytes a piece with the nodes). On cornell_smoke (128^2,
    // 1 spp, 1 thread) 16 r with 16 pieces a leaf took 0.85x the time and 1/3 of the
    // memory of 8 r with 4 a leaf; 4 r, 32 r and 64 r were slower (the query's cost is
    // the nodes and pieces near the camera ray, ~1000 node visits for ~65 candidates).
    double total = 0.0;
    for (const MediumBeam& b : beams) total += double(b.length);
    const double diag = double(scene.bounds().diagonal());
    const double piece = std::max({16.0 * double(r), (std::isfinite(diag) ? diag : 0.0) / 128.0, total / 8e6});
    bvh.build(std::move(beams), float(piece));
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
