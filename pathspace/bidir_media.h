// Participating media in the bidirectional layer (vertex convention and the free-flight
// factors in bidir_vertex.h; issue 15, docs/media_next_plan.md).
//
// Path integral (Gruson et al. 2018, Sec. 3.1, Eqs. 2-4; Pauly et al. 2000): a medium
// vertex contributes sigma_s rho_p (the phase function, no cosine), every edge the
// transmittance Tr = prod exp(-int sigma_t) of the media it crosses. A walk samples each
// edge's end by a free flight: a scatter at distance t has density p(t) (per unit length;
// with the direction's solid-angle density and 1/t^2 a volume density at the medium
// vertex), a surface reached through a medium has probability P(pass). The walk's
// throughput grows by Tr sigma_s / p(t) or Tr / P(pass); the MIS densities (Veach 1997,
// Eq. 10.9) get p(t) or P(pass) as "end factors" -- for both walks along the edge, since
// a connection or a strategy of the other side crosses the same segment in the other
// direction and ends at the other vertex. Index-matched boundaries (`material: none`)
// are not vertices: every sub-segment but the last (in the walk's direction) is passed,
// P(pass); the last ends at the vertex.
//
// Homogeneous media: the free flight of scene/media/free_flight.h (one-sample mixture
// over the RGB channels), whose p(t) and P(pass) are exact closed forms of the length.
//
// Grid media (scene/media/grid_tracking.h): walks sample free flights by delta tracking
// (throughput x albedo at a scatter, x 1 on a pass); the transmittance of an edge whose
// value multiplies a contribution (connections, light tracing to the pinhole) is a
// ratio-tracking estimate (needs a GridTracking with an rng). Delta tracking's densities
// are p(t) = sigma_t(t) Tr(t) and P(pass) = Tr, with Tr = exp(-tau) not known in closed
// form. The MIS weights of one path only need to be a partition of unity over the
// strategies that can sample it for the estimator to stay unbiased (Veach 1997,
// Sec. 9.2: any such weights do; the balance/power heuristics are merely the good
// choices), so the end factors of a grid sub-segment a-b use a DETERMINISTIC stand-in:
//   tau_hat(a, b) = midpoint quadrature of int sigma_t over [a, b] clipped to the grid's
//                   box, kGridSteps equal steps whatever its length (a step count that changed
//                   with the length would jump between a walk's and a re-trace's float
//                   crossing points, and the weights would miss 1 there), the
//                   endpoints taken in a fixed (lexicographic) order so that
//                   tau_hat(a, b) == tau_hat(b, a) bit for bit;
//   P(pass) ~ exp(-tau_hat),   p(t) at the medium vertex x ~ sigma_t(x) exp(-tau_hat),
// a function of the sub-segment's endpoints only, the same whether a walk computes it
// (FlightChain) or trace_edge re-traces it from positions, from either side. Strategies
// weighted with it stay unbiased; only their variance departs from the balance/power
// heuristic's by the quadrature error. pbrt-v3's BDPT likewise leaves medium densities
// out of (approximates) its MIS. MIS-only callers pass no rng and stay deterministic.
//
// A light at infinity seen through a medium that reaches infinity is fully attenuated
// (Tr(inf) = 0 for sigma_t > 0): light walks from such a light in a medium end at once.
#pragma once

#include "core/rng.h"
#include "pathspace/bidir_vertex.h"

namespace dp::pathspace {

// Index-matched boundaries a walk or a connection passes between two vertices before it
// ends (numerical trouble), as volpath's kMaxNullCrossings.
constexpr int kMaxEdgeCrossings = 256;

// Steps of the grid media's optical-depth quadrature (header comment). Only the MIS
// weights' quality depends on it (not unbiasedness). bdpt on cornell_smoke with a 64^3 grid,
// 16 spp: 11.9 s with 16 steps, 26.7 s with half-voxel steps (6.4 s homogeneous).
constexpr int kGridSteps = 16;

// The endpoints of a sub-segment: a to b, or (to_infinity) from a along unit direction b.
struct Span {
  Vec3 a{0, 0, 0}, b{0, 0, 0};
  bool to_infinity = false;
  static Span between(const Vec3& a, const Vec3& b) { return Span{a, b, false}; }
  static Span ray(const Vec3& a, const Vec3& d) { return Span{a, d, true}; }
};

// Randomness and counts for grid media (header comment). `rng` null: no estimate can be
// drawn; trace_edge's tr of a grid medium is then exp(-tau_hat) (deterministic, for
// MIS-only callers; biased as a contribution's factor).
struct GridTracking {
  core::Rng* rng = nullptr;
  bool ratio_tracking = true;  // false: BidirFault::connection_without_ratio_tracking (Tr = 1 in grids)
  int64_t flights = 0;         // free flights by delta tracking (walks)
  int64_t ratio_estimates = 0; // transmittance estimates by ratio tracking (edges)
};

// tau_hat of a grid medium over `span` (header comment).
float grid_optical_depth(const scene::HomogeneousMedium& m, const Span& span);

// The end factor of a sub-segment `span` of length `len` in `medium` (-1: vacuum, 1):
// p(len) at a medium vertex, P(pass) otherwise (scene/media/free_flight.h); the vertex is
// at span.b, or at span.a with `vertex_at_a`. Grid media: the stand-ins of the header
// comment (`len` unused); homogeneous media: `span` unused.
float end_factor(const scene::Scene& scene, int medium, float len, const Span& span, bool at_medium_vertex,
                 bool vertex_at_a = false);

// The medium a ray leaving vertex v along unit world direction w starts in.
int medium_toward(const scene::Scene& scene, const BidirVertex& v, const Vec3& w);

// The end factors of one sub-segment a-b: P(pass), and p at a medium vertex at a or b.
struct SpanFactors {
  float pass = 1, at_a = 1, at_b = 1;
};

// Products of free-flight factors over the sub-segments of one edge from vertex a to
// vertex b (in walk order a -> b), built one sub-segment at a time.
class FlightChain {
 public:
  // A sub-segment that ends at an index-matched boundary (not the last one). pass and
  // finish return the sub-segment's P(pass).
  float pass(const scene::Scene& scene, int medium, float len, const Span& span);
  // The last sub-segment (ending at b). a_medium / b_medium: a / b are medium vertices.
  // Sets the factors: to_b, the density factor of the walk a -> b (b's ff_fwd when a
  // precedes b in b's walk), and to_a, that of the walk b -> a.
  float finish(const scene::Scene& scene, int medium, float len, const Span& span, bool a_medium, bool b_medium);
  float to_b = 1, to_a = 1;

 private:
  int m_n = 0;                  // sub-segments passed so far
  int m_first_medium = -1;
  SpanFactors m_first;          // of the first sub-segment (at_a: a medium vertex a)
  float m_pass_all = 1;         // P(pass) of every passed sub-segment
  float m_pass_after_first = 1; // ... but the first
};

// A segment between two vertices traced through index-matched boundaries.
struct EdgeMedia {
  bool blocked = false;       // an opaque or refractive surface (or too many boundaries)
  Rgb tr = Rgb::Ones();       // transmittance of every medium crossed (Beer-Lambert; grids: GridTracking)
  float to_b = 1, to_a = 1;   // FlightChain's factors
  int b_medium = -1;          // the medium the segment arrives at b through
  int crossings = 0;          // index-matched boundaries passed
};
// Traces a -> b (a finite; b may be a light at infinity: then along b.sp.ng to infinity).
// The rays leave a and end short of b by the scene's epsilon, as Scene::occluded and
// Scene::spawn_segment; sub-segment lengths are the distances between the crossing points.
// `grid`: the rng for ratio tracking in grid media and its counts (null: MIS only;
// GridTracking).
EdgeMedia trace_edge(const scene::Scene& scene, const BidirVertex& a, const BidirVertex& b,
                     GridTracking* grid = nullptr);

// Solid-angle density of sampling direction `to` at vertex v (surface: the BSDF in
// `mode`; medium: the phase function), having arrived from `from` (both away from v).
float scatter_pdf(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to,
                  scene::TransportMode mode);
// The phase function rho_p at medium vertex v for light arriving from `from` (away from
// v) and leaving along `to`.
float phase_value(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to);

}  // namespace dp::pathspace
