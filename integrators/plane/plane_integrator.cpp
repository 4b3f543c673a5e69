#include "integrators/plane/plane_integrator.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "integrators/beam/beam_bvh.h"
#include "integrators/media_photons/media_photon_render.h"
#include "integrators/plane/plane_bvh.h"
#include "integrators/plane/plane_gather.h"
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
    PhotonTraceParams tp = params;
    tp.store_photons = false;
    std::vector<MediumPhoton> none;
    std::vector<MediumBeam> beams;
    std::vector<MediumPlane> planes;
    BeamTraceCounters bc;
    PlaneTraceCounters plc;
    if (!trace_medium_photons(scene, tp, options.stop, none, pc, nullptr, &beams, &bc, nullptr, &planes, &plc))
      return false;
    // Beams from scattering events carry the planes' light (plane_gather.h): left out.
    const bool keep_all = m_settings.fault == PlaneFault::beams_after_scatter;
    const size_t all = beams.size();
    beams.erase(
        std::remove_if(beams.begin(), beams.end(), [&](const MediumBeam& b) { return b.after_scatter && !keep_all; }),
        beams.end());
    stats.add("plane.beams_stored", int64_t(beams.size()));
    stats.add("plane.beams_to_planes", int64_t(all - beams.size()));
    stats.add("plane.beams_clipped", bc.clipped);
    stats.add("plane.beam_nan_dropped", bc.dropped);
    stats.add("plane.planes_stored", plc.stored);
    stats.add("plane.planes_clipped", plc.clipped);
    stats.add("plane.plane_dropped", plc.dropped);
    // Beam pieces as `beam` (beam_integrator.cpp); plane pieces >= piece_scale x diag.
    double total = 0.0;
    for (const MediumBeam& b : beams) total += double(b.length);
    const double diag = double(scene.bounds().diagonal());
    const double d = std::isfinite(diag) ? diag : 0.0;
    beam_bvh.build(std::move(beams), float(std::max({16.0 * double(r), d / 128.0, total / 8e6})));
    plane_bvh.build(std::move(planes), float(m_settings.piece_scale * d));
    stats.add("plane.beam_pieces", int64_t(beam_bvh.pieces()));
    stats.add("plane.plane_pieces", int64_t(plane_bvh.pieces()));
    gather = std::make_unique<PlaneGather>(scene, m_settings, beam_settings, beam_bvh, plane_bvh, r, tp.paths);
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
  // Present (0) also when no light pass ran (no media, or no complete iteration).
  for (const char* k : {"plane.beams_stored", "plane.beams_to_planes", "plane.beams_clipped", "plane.beam_nan_dropped",
                        "plane.planes_stored", "plane.planes_clipped", "plane.plane_dropped", "plane.beam_pieces",
                        "plane.plane_pieces"})
    r.stats.add(k, 0);
  r.info["kernel"] = "planes 0d + beams 3d";
  r.info["plane_piece_scale"] = m_settings.piece_scale;
  return r;
}

RenderResult PlaneIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);
}

}  // namespace dp::integrators
