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
//    In a grid medium (scene/media/grid_tracking.h) the flight is delta tracking: weight
//    sigma_s / sigma_t (the albedo) at a scatter, 1 on a pass -- the same expectations.
//    Beams are grid-aware in beam/beam_gather.h, planes in photon_plane.h (record_plane_grid).
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
//  * Photon beams (`beam`; Jarosz et al. 2011; only when asked for, as the parent records):
//    every segment a light path travels inside a medium with sigma_s > 0 is also stored as
//    a short beam, from its start a (the light, a surface vertex, a scattering event or an
//    index-matched boundary) to the free flight's end (the sampled scattering event, or
//    the surface when the flight passed), with the throughput beta_a at a (before the
//    free-flight weight, sigma_s not included) and the segment's depth s (a photon at the
//    beam's end has the same s). Recording draws no random number: photons, paths and
//    counters are bit-identical with and without beams. Beams are clipped to the scene's
//    bounds grown by one diagonal on every side (counted): in a closed medium this never
//    happens; in an unbounded one (a camera-medium fog) a flight may end 1e4 units away or
//    never (a channel with sigma_t = 0), and the light scattered outside that box is left
//    out (the only truncation: a bias of unbounded media; the kept part is [begin, length]
//    of the original parameter, so Tr(v) / P(v) stays that of the whole flight).
//    Short beams are unbiased for the fluence along the segment (derivation in
//    beam/beam_gather.h): a point at distance v < t_surf from a is covered iff the free
//    flight passed it, with probability P(v) = 1/3 sum_c exp(-sigma_t[c] v) (free_flight.h's
//    one-channel mixture), so the weight beta_a Tr(v) / P(v) has expectation beta_a Tr(v).
//    A beam records whether it starts at a scattering event (after_scatter): `plane`
//    leaves those beams' light to its planes.
//  * Photon planes (`plane`; photon_plane.h; only when asked for): at every scattering
//    event that continues (phase sample drawn, roulette survived), the segment it lies on
//    and the sampled direction, with P_s and q; the plane's extent D along w1 is drawn from
//    a stream of its own, so nothing else changes. In a grid medium every medium segment
//    below the last depth makes a plane with a probability of its own, all its random
//    numbers from that stream too (photon_plane.h, record_plane_grid).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/stats.h"
#include "gradients/volume_photon_chain.h"
#include "integrators/media_photons/photon_plane.h"
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

// One light-path segment inside a medium (a short photon beam): the points a + v w,
// v in [0, length]. See the header comment.
struct MediumBeam {
  Vec3 a{0, 0, 0};         // start
  Vec3 w{0, 0, 1};         // unit direction the light travels
  float length = 0;        // to the scattering event or the surface (finite; clipped)
  float begin = 0;         // the kept part is v in [begin, length] (begin > 0 only when clipped)
  Rgb beta = Rgb::Zero();  // throughput per emitted path at a (no sigma_s)
  int16_t depth = 0;       // the segment's index from the light (MediumPhoton::depth's convention)
  int16_t medium = -1;     // index into Scene::media()
  uint32_t index = 0;      // position in the traced order
  bool after_scatter = false;  // a starts at a medium scattering event (`plane` leaves these to planes)
};

struct BeamTraceCounters {
  int64_t stored = 0;    // beams recorded
  int64_t clipped = 0;   // flights clipped to the grown scene bounds (or dropped: wholly outside)
  int64_t dropped = 0;   // non-finite start, direction or weight: not recorded
  BeamTraceCounters& operator+=(const BeamTraceCounters& o) {
    stored += o.stored;
    clipped += o.clipped;
    dropped += o.dropped;
    return *this;
  }
};

struct PhotonTraceCounters {
  int64_t paths = 0, stored = 0, surface_events = 0, null_crossings = 0, rr_terminated = 0, null_limit = 0;
  int64_t nan_dropped = 0;  // photons with a non-finite weight, never stored
  int64_t grid_flights = 0; // free flights in grid media (delta tracking)
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
  bool store_photons = true;  // false: no photon is kept (`beam` keeps only beams; same paths)
};

// Traces params.paths light paths into `out` (cleared); false if `stop` interrupted it.
// With `parents`, (*parents)[photon.index] is each photon's parent record. With `beams`,
// every medium segment's short beam (in chunk order, beam.index its position), counted in
// *beam_counters (required with `beams`). With `beam_parents` (needs `parents` and
// `beams`), (*beam_parents)[beam.index] is the vertex each beam's light path left last
// (the parent of every photon on the beam; G-Beam's reconnection). With `planes`, every
// scattering event's photon plane (photon_plane.h; its D from a stream of its own, so
// photons, beams and paths are bit-identical with and without planes), counted in
// *plane_counters (required). With `chains` (needs `parents`), the specular chains of
// photons behind purely specular surfaces (volume_photon_chain.h; PhotonParent::chain
// indexes them); recording draws no random number.
bool trace_medium_photons(const scene::Scene& scene, const PhotonTraceParams& params, const std::atomic<bool>* stop,
                          std::vector<MediumPhoton>& out, PhotonTraceCounters& counters,
                          std::vector<gradients::PhotonParent>* parents = nullptr,
                          std::vector<MediumBeam>* beams = nullptr, BeamTraceCounters* beam_counters = nullptr,
                          std::vector<gradients::PhotonParent>* beam_parents = nullptr,
                          std::vector<MediumPlane>* planes = nullptr, PlaneTraceCounters* plane_counters = nullptr,
                          std::vector<gradients::PhotonChain>* chains = nullptr);

// The part [t0, t1] of the ray o + t d (d unit) inside the scene's bounds grown by one
// diagonal on every side (the clip of beams and planes); t0 > t1 if it misses.
void grown_bounds_clip(const scene::Scene& scene, const Vec3& o, const Vec3& d, float& t0, float& t1);

}  // namespace dp::integrators
