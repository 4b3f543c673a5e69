// Homogeneous participating media in the bidirectional layer (vertex convention and the
// free-flight factors in bidir_vertex.h; issue 15, docs/media_next_plan.md).
//
// Path integral (Gruson et al. 2018, Sec. 3.1, Eqs. 2-4; Pauly et al. 2000): a medium
// vertex contributes sigma_s rho_p (the phase function, no cosine), every edge the
// transmittance Tr = prod exp(-sigma_t L) of the media it crosses. A walk samples each
// edge's end by the free flight of scene/media/free_flight.h (one-sample mixture over
// the RGB channels): a scatter at distance t has density p(t) (per unit length; with the
// direction's solid-angle density and 1/t^2 a volume density at the medium vertex), a
// surface reached through a medium has probability P(pass). The walk's throughput
// grows by Tr sigma_s / p(t) or Tr / P(pass); the MIS densities (Veach 1997, Eq. 10.9)
// get p(t) or P(pass) as "end factors" -- for both walks along the edge, since a
// connection or a strategy of the other side crosses the same segment in the other
// direction and ends at the other vertex. Index-matched boundaries (`material: none`)
// are not vertices: every sub-segment but the last (in the walk's direction) is passed,
// P(pass); the last ends at the vertex.
//
// Grid media are not supported here (their p(t) is not known in closed form; the bdpt
// integrator refuses them). A light at infinity seen through a medium that reaches
// infinity is fully attenuated (Tr(inf) = 0 for sigma_t > 0): light walks from such a
// light in a medium end at once.
#pragma once

#include "pathspace/bidir_vertex.h"

namespace dp::pathspace {

// Index-matched boundaries a walk or a connection passes between two vertices before it
// ends (numerical trouble), as volpath's kMaxNullCrossings.
constexpr int kMaxEdgeCrossings = 256;

// The end factor of a sub-segment of length `len` in `medium` (-1: vacuum, 1):
// p(len) at a medium vertex, P(pass) otherwise (scene/media/free_flight.h).
float end_factor(const scene::Scene& scene, int medium, float len, bool at_medium_vertex);

// The medium a ray leaving vertex v along unit world direction w starts in.
int medium_toward(const scene::Scene& scene, const BidirVertex& v, const Vec3& w);

// Products of free-flight factors over the sub-segments of one edge from vertex a to
// vertex b (in walk order a -> b), built one sub-segment at a time.
class FlightChain {
 public:
  // A sub-segment that ends at an index-matched boundary (not the last one).
  void pass(const scene::Scene& scene, int medium, float len);
  // The last sub-segment (ending at b). a_medium / b_medium: a / b are medium vertices.
  // Sets the factors: to_b, the density factor of the walk a -> b (b's ff_fwd when a
  // precedes b in b's walk), and to_a, that of the walk b -> a.
  void finish(const scene::Scene& scene, int medium, float len, bool a_medium, bool b_medium);
  float to_b = 1, to_a = 1;

 private:
  int m_n = 0;                  // sub-segments passed so far
  int m_first_medium = -1;
  float m_first_len = 0;
  float m_pass_all = 1;         // P(pass) of every passed sub-segment
  float m_pass_after_first = 1; // ... but the first
};

// A segment between two vertices traced through index-matched boundaries.
struct EdgeMedia {
  bool blocked = false;       // an opaque or refractive surface (or too many boundaries)
  Rgb tr = Rgb::Ones();       // Beer-Lambert transmittance of every medium crossed
  float to_b = 1, to_a = 1;   // FlightChain's factors
  int b_medium = -1;          // the medium the segment arrives at b through
  int crossings = 0;          // index-matched boundaries passed
};
// Traces a -> b (a finite; b may be a light at infinity: then along b.sp.ng to infinity).
// The rays leave a and end short of b by the scene's epsilon, as Scene::occluded and
// Scene::spawn_segment; sub-segment lengths are the distances between the crossing points.
EdgeMedia trace_edge(const scene::Scene& scene, const BidirVertex& a, const BidirVertex& b);

// Solid-angle density of sampling direction `to` at vertex v (surface: the BSDF in
// `mode`; medium: the phase function), having arrived from `from` (both away from v).
float scatter_pdf(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to,
                  scene::TransportMode mode);
// The phase function rho_p at medium vertex v for light arriving from `from` (away from
// v) and leaving along `to`.
float phase_value(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to);

}  // namespace dp::pathspace
