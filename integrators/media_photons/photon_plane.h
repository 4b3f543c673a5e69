// Photon planes recorded by the light tracer (`plane`; Bitterli & Jarosz 2017, "Beyond
// points and beams"; the primal Plane of Gruson et al. 2018, Sec. 5.3). At a medium
// scattering event a1 on the segment a0 + t w0 (t in [0, t_surf), t_surf the first surface
// or +inf), once the phase function has drawn w1 and the path survived roulette at a1 (with
// probability q), the plane {a0 + t0 w0 + t1 w1 : t0 in [0, t_surf), t1 in [0, D]} is kept.
// The plane forgets where a1 was: every point of the segment acts as a1 (the segment as a
// long beam, weight Tr(t0)), so it is produced with probability
//   P_s q,   P_s = 1 - P(pass t_surf) = 1 - 1/3 sum_c exp(-sigma_t[c] t_surf)
// (free_flight.h's channel mixture) and is weighted 1 / (P_s q) (plane/plane_gather.h).
// D is a fresh untruncated free-flight distance (channel uniform, exponential in it), drawn
// from a stream of its own: P(D > t1) = P_pass(t1), so a point at t1 is covered with that
// probability whatever a1 is, and the weight Tr(t1) / P_pass(t1) is unbiased (the short-beam
// argument of beam/beam_gather.h along w1). Clipped to the scene's bounds grown by one
// diagonal as beams are (photon_tracer.h): t0 to the segment's part inside, t1 to where
// the plane (over that t0 range) may still be inside (a per-axis bound); a plane wholly
// outside is dropped and counted. Only in an unbounded medium does that leave light out.
//
// Grid media (record_plane_grid; the estimator and why it is unbiased: plane/plane_gather.h,
// "Grid media"). P_s = 1 - Tr(t_surf) and Tr along w1 from a point that moves with t0 have
// no closed form, so a grid plane is made differently, from `plane_rng` alone (the light
// path's stream is untouched):
//  * for every medium segment of depth < max (not only those that scattered), kept with
//    the closed-form probability P_rec = 1 - exp(-mu L) (mu = sigma_t x the grid's maximum
//    density, L the segment's length inside the grid's box: the majorant's chance of a
//    collision there, >= P_s; = P_s in a constant grid); q = 1 (no roulette involved);
//  * w1 drawn from the phase function around w0 (HG's weight rho / p = 1; the phase is
//    the same everywhere);
//  * t0 restricted to the segment's part inside the box (sigma_s(a1) = 0 outside), Tr(t0)
//    from a ratio-tracking profile along w0 (tentative collisions t0_i and the running
//    products v_i); t0_end cut at the first collision where the product is 0 (beyond it
//    every estimate is 0);
//  * along w1 the tentative collisions t1_j of rate mu (the same for every t0), from 0 to
//    the per-axis bound of the box over the t0 range, each kept with the t0-independent
//    probability c = 1 - min density / max density; the first one not kept ends the plane
//    (t1_end). At a hit, Tr(t0, t1) is estimated by prod_{t1_j < t1} (1 - sigma_t(a1 +
//    t1_j w1) / mu) / c: ratio tracking with a roulette per collision whose survival
//    probability c bounds every factor (inside the box, where both plane points must be).
// The t's and products are kept in `grid`: [t0_i (n0), v_i (n0), t1_j (the rest)].
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "scene/media/medium.h"
#include "scene/scene.h"

namespace dp::integrators {

struct MediumPlane {
  Vec3 a0{0, 0, 0};                // the segment's start (light, surface, scattering event or boundary)
  Vec3 w0{0, 0, 1};                // unit direction of the segment
  Vec3 w1{0, 0, 1};                // unit direction sampled at the scattering event on it
  float t0_begin = 0, t0_end = 0;  // the kept part of the segment (t_surf, clipped)
  float t1_end = 0;                // min(D, clip)
  float p_scatter = 1;             // P_s
  float q = 1;                     // roulette survival at a1
  Rgb beta = Rgb::Zero();          // throughput per emitted path at a0 (no sigma_s)
  int16_t depth = 0;               // the depth of a point b on the plane (the segment's + 1)
  int16_t medium = -1;
  uint32_t index = 0;  // position in the traced order
  // Grid media only (record_plane_grid; the medium says which): `grid` empty otherwise.
  uint32_t grid_n0 = 0;     // ratio-tracking collisions along w0
  float grid_c = 1;         // survival probability of a tentative collision along w1
  std::vector<float> grid;  // t0_i (n0), Tr_hat after each (n0), kept t1_j (rest); ascending
};

struct PlaneTraceCounters {
  int64_t stored = 0, clipped = 0, dropped = 0;  // dropped: non-finite, or wholly outside the bounds
  int64_t grid = 0;                              // of `stored`, planes in grid media
  PlaneTraceCounters& operator+=(const PlaneTraceCounters& o) {
    stored += o.stored;
    clipped += o.clipped;
    dropped += o.dropped;
    grid += o.grid;
    return *this;
  }
};

// The untruncated free-flight distance of free_flight.h's sampler from (u_channel, u).
float free_flight_distance(const scene::HomogeneousMedium& med, float u_channel, float u);

// Appends the plane of the segment (a0, w0, t_surf) with w1 sampled at its scattering
// event (see the header comment); `depth_b` is the depth of the plane's points.
void record_plane(const scene::Scene& scene, const scene::HomogeneousMedium& med, const Vec3& a0, const Vec3& w0,
                  float t_surf, const Vec3& w1, const Rgb& beta_a0, float q, int depth_b, int medium, float u_channel,
                  float u, std::vector<MediumPlane>& planes, PlaneTraceCounters& counters);

// A grid medium's plane of the segment (a0, w0, t_surf) whose start has throughput
// `beta_a0` (see the header comment), its points of depth `depth_b`; every random number
// from `rng`.
void record_plane_grid(const scene::HomogeneousMedium& med, const Vec3& a0, const Vec3& w0, float t_surf, const Rgb& beta_a0, int depth_b, int medium, core::Rng& rng,
                       std::vector<MediumPlane>& planes, PlaneTraceCounters& counters);

}  // namespace dp::integrators
