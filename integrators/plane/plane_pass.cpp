#include "integrators/plane/plane_pass.h"

#include "integrators/beam/beam_gather.h"  // beam_piece_length

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace dp::integrators {

void PlanePassCounters::flush(core::Stats& stats, const std::string& prefix) const {
  stats.add(prefix + ".beams_stored", beams_stored);
  stats.add(prefix + ".beams_to_planes", beams_to_planes);
  stats.add(prefix + ".beams_clipped", beams_clipped);
  stats.add(prefix + ".beam_nan_dropped", beam_nan_dropped);
  stats.add(prefix + ".planes_stored", planes_stored);
  stats.add(prefix + ".planes_clipped", planes_clipped);
  stats.add(prefix + ".plane_dropped", plane_dropped);
  stats.add(prefix + ".beam_pieces", beam_pieces);
  stats.add(prefix + ".plane_pieces", plane_pieces);
  if (grid_planes > 0) stats.add(prefix + ".grid_planes", grid_planes);
}

bool trace_plane_pass(const scene::Scene& scene, const PhotonTraceParams& params, const std::atomic<bool>* stop,
                      float radius, double piece_scale, bool keep_scatter_beams, PhotonTraceCounters& photon_counters,
                      PlanePassCounters& counters, BeamBvh& beam_bvh, PlaneBvh& plane_bvh) {
  PhotonTraceParams tp = params;
  tp.store_photons = false;
  std::vector<MediumPhoton> none;
  std::vector<MediumBeam> beams;
  std::vector<MediumPlane> planes;
  BeamTraceCounters bc;
  PlaneTraceCounters plc;
  if (!trace_medium_photons(scene, tp, stop, none, photon_counters, nullptr, &beams, &bc, nullptr, &planes, &plc))
    return false;
  const size_t all = beams.size();
  beams.erase(std::remove_if(beams.begin(), beams.end(),
                             [&](const MediumBeam& b) { return b.after_scatter && !keep_scatter_beams; }),
              beams.end());
  counters.beams_stored += int64_t(beams.size());
  counters.beams_to_planes += int64_t(all - beams.size());
  counters.beams_clipped += bc.clipped;
  counters.beam_nan_dropped += bc.dropped;
  counters.planes_stored += plc.stored;
  counters.planes_clipped += plc.clipped;
  counters.plane_dropped += plc.dropped;
  counters.grid_planes += plc.grid;
  // Beam pieces as `beam`'s; plane pieces >= piece_scale x diag.
  const float piece = beam_piece_length(scene, beams, radius);
  beam_bvh.build(std::move(beams), piece);
  const double diag = double(scene.bounds().diagonal());
  plane_bvh.build(std::move(planes), float(piece_scale * (std::isfinite(diag) ? diag : 0.0)));
  counters.beam_pieces += int64_t(beam_bvh.pieces());
  counters.plane_pieces += int64_t(plane_bvh.pieces());
  return true;
}

}  // namespace dp::integrators
