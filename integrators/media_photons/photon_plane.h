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
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
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
};

struct PlaneTraceCounters {
  int64_t stored = 0, clipped = 0, dropped = 0;  // dropped: non-finite, or wholly outside the bounds
  PlaneTraceCounters& operator+=(const PlaneTraceCounters& o) {
    stored += o.stored;
    clipped += o.clipped;
    dropped += o.dropped;
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

}  // namespace dp::integrators
