// Photons in participating media (`vpm`, `bre`): light paths traced from the lights
// through homogeneous media, stored at their medium scattering events.
//  * Emission as the bidirectional light subpaths (pathspace::emit_light_ray): beta_0 =
//    Le |cos| / (p(y_0) p(direction)), in power units per emitted path.
//  * The medium a light ray starts in is read off the first surface it reaches: the
//    side it arrives from if that surface is a medium boundary, else the camera's medium
//    (scene/media/medium_interface.h's default for undeclared sides).
//  * In a medium, each segment samples a free flight (scene/media/free_flight.h): a scatter
//    before the next surface multiplies beta by Tr sigma_s / p(t) (Gruson et al. 2018,
//    Eqs. 2-3: the edge's tau and the medium vertex's sigma_s) and stores a photon (b in
//    Eq. 5) there, then samples the phase function (weight 1); a pass multiplies by
//    Tr / P(pass). So the expected photon weight per volume and solid angle is
//    sigma_s(x) L(x, w): the in-scattered radiance at x is
//      sigma_s L_i(x, w_o) ~ 1/N sum_k rho_p(w_k, w_o) beta_k K(x - y_k)   (Eq. 5, D)
//    with N the emitted paths.
//  * Surfaces as volpath's walk in reverse: BSDF sampling in importance mode, index-
//    matched boundaries switch the medium and cost no depth; Russian roulette after
//    rr_depth segments on beta relative to beta_0.
//  * A photon records its depth s = segments from the light (the first medium vertex
//    after emission is s = 1); a camera path reaching its gather point in t segments
//    uses only photons with s + t <= max_depth (volpath's path length), so photons of
//    depth >= max_depth are never stored.
// Deterministic: paths are traced in fixed chunks, each with its own stream (seed,
// iteration, chunk), and listed in chunk order.
//  * Parent records (G-VPM, docs/gvpm_plan.md step 4; only when asked for: `vpm`/`bre`
//    do not pay for them): each photon's parent y_{s-1} (light, surface or medium vertex,
//    and whether the photon can be reconnected to it: gradients::PhotonParent) in a
//    separate array indexed by MediumPhoton::index (the BVH reorders the photons). The
//    light endpoint is re-drawn from a copy of the path's stream by
//    pathspace::light_subpath, which draws exactly as emit_light_ray does, so the photons
//    and their weights are bit-identical with and without records.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/stats.h"
#include "gradients/volume_photon_reconnect.h"
#include "scene/scene.h"

namespace dp::integrators {

struct MediumPhoton {
  Vec3 p{0, 0, 0};   // the scattering point y_s
  Vec3 w{0, 0, 1};   // unit direction the light travelled to reach it
  Rgb beta = Rgb::Zero();  // throughput per emitted path (sigma_s at p included)
  int16_t depth = 0;       // segments from the light
  int16_t medium = -1;     // index into Scene::media()
  uint32_t index = 0;      // position in the traced order (the parent records' index)
};

struct PhotonTraceCounters {
  int64_t paths = 0, stored = 0, surface_events = 0, null_crossings = 0, rr_terminated = 0, null_limit = 0;
  int64_t nan_dropped = 0;  // photons with a non-finite weight, never stored
  PhotonTraceCounters& operator+=(const PhotonTraceCounters& o);
  void flush(core::Stats& stats, const std::string& prefix) const;
};

struct PhotonTraceParams {
  int64_t paths = 0;   // light paths N
  int max_depth = 8;   // RenderOptions::max_depth
  int rr_depth = 5;
  uint64_t seed = 0;
  int64_t iteration = 0;
  int threads = 1;
};

// Traces params.paths light paths into `out` (cleared); false if `stop` interrupted it.
// With `parents`, (*parents)[photon.index] is each photon's parent record.
bool trace_medium_photons(const scene::Scene& scene, const PhotonTraceParams& params, const std::atomic<bool>* stop,
                          std::vector<MediumPhoton>& out, PhotonTraceCounters& counters,
                          std::vector<gradients::PhotonParent>* parents = nullptr);

}  // namespace dp::integrators
