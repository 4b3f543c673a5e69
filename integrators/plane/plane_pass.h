// One light pass of photon planes (`plane`, `gplane`): the light paths of one iteration
// traced with planes and beams (media_photons/photon_tracer.h), the beams that start at a
// scattering event dropped (their light is the planes', plane_gather.h), and both kept in
// their BVHs: beam pieces as `beam`'s (beam_piece_length), plane pieces at least
// piece_scale x the scene diagonal on a side (plane_bvh.h).
#pragma once

#include <atomic>
#include <string>

#include "core/stats.h"
#include "integrators/beam/beam_bvh.h"
#include "integrators/media_photons/photon_tracer.h"
#include "integrators/plane/plane_bvh.h"

namespace dp::integrators {

struct PlanePassCounters {
  int64_t beams_stored = 0, beams_to_planes = 0, beams_clipped = 0, beam_nan_dropped = 0;
  int64_t planes_stored = 0, planes_clipped = 0, plane_dropped = 0, beam_pieces = 0, plane_pieces = 0;
  int64_t grid_planes = 0;  // of planes_stored, those in grid media (photon_plane.h, record_plane_grid)
  // Adds <prefix>.beams_stored, ... (every key, also when 0; grid_planes only when > 0).
  void flush(core::Stats& stats, const std::string& prefix) const;
};

// False (nothing built) when `stop` interrupted the tracing. `keep_scatter_beams`: the
// planted defect PlaneFault::beams_after_scatter (their light counted twice).
bool trace_plane_pass(const scene::Scene& scene, const PhotonTraceParams& params, const std::atomic<bool>* stop,
                      float radius, double piece_scale, bool keep_scatter_beams, PhotonTraceCounters& photon_counters,
                      PlanePassCounters& counters, BeamBvh& beams, PlaneBvh& planes);

}  // namespace dp::integrators
