// Multiple importance sampling weights of bidirectional strategies (vertex convention
// in bidir_vertex.h). For the path x of strategy (s, t), with p_i the density of x as
// sampled by strategy (i, s + t - i):
//   w_s = p_s^b / sum_i p_i^b          (Veach 1997, Eq. 9.13 / 10.9; b = 1 balance, 2 power)
// computed with Veach's explicit ratios (Sec. 10.2.1, Eq. 10.9-10.10): moving the
// connection one vertex toward the camera multiplies p by pdf_rev(z_i) / pdf_fwd(z_i),
// one vertex toward the light by pdf_rev(y_i) / pdf_fwd(y_i). A strategy whose
// connection would touch a vertex scattered through a Dirac lobe, or hit a delta-position
// light (s = 0), cannot generate the path and is left out of the sum (weight 0); t = 0
// (hitting the pinhole) is never counted. The pdf_rev of the connection vertices and
// their predecessors is recomputed here from the geometry of the connection.
#pragma once

#include <cstdint>

#include "pathspace/bidir_vertex.h"

namespace dp::pathspace {

enum class MisHeuristic : uint8_t { balance, power };

// Deliberate defects the tests must reject (tests/integrators/test_bdpt_*.cpp). C++ only:
// no setting reaches them; `none` leaves every image bit-identical.
enum class BidirFault : uint8_t {
  none,
  mis_without_light_tracing,   // the t = 1 strategy is left out of every other strategy's sum
  reverse_pdf_without_cosine,  // the recomputed reverse area densities miss |cos| at the target
  connection_without_cosine,   // a connection's scattering factors miss |cos| (bidir_connect.cpp)
  splat_pixel_rounded,         // light-tracing splats go to the nearest pixel corner's pixel (bdpt_tracer.cpp)
  light_tracing_at_infinity,   // an environment seen directly counts the impossible (1, 1) strategy
  reverse_pdf_without_free_flight,  // the recomputed reverse densities miss the free-flight factors (media)
  connection_without_transmittance,  // a connection's value misses the transmittance of its media (bidir_connect.cpp)
  connection_without_ratio_tracking,  // grid media on connections pass with Tr = 1 (bdpt_tracer.cpp: GridTracking)
};

struct MisConfig {
  MisHeuristic heuristic = MisHeuristic::power;
  BidirFault fault = BidirFault::none;
  bool unweighted = false;  // every strategy's weight is 1 (one strategy rendered alone)
};

// Reverse area densities a connection (s, t) implies (Veach 1997, Sec. 10.2: the
// densities the other side would have used): z_rev[0] of camera[t-1] generated from the
// light side, z_rev[1] of camera[t-2] generated from camera[t-1] arriving from the light
// side; y_rev[0], y_rev[1] likewise for light[s-1], light[s-2]. For s = 0, camera[t-1] acts
// as the light endpoint (light selection x position; emission toward camera[t-2]).
// Unused entries stay 0. `cosine` = false is BidirFault::reverse_pdf_without_cosine.
// With media each density gets the free-flight factor of its edge (bidir_media.h): the
// connection's from `edge` (traced here if null), the predecessors' from ff_rev.
struct ReversePdfs {
  float z[2] = {0, 0}, y[2] = {0, 0};
};
struct EdgeMedia;
ReversePdfs connection_reverse_pdfs(const scene::Scene& scene, const BidirVertex* light, int s,
                                    const BidirVertex* camera, int t, bool cosine = true,
                                    const EdgeMedia* edge = nullptr, bool free_flight = true);
// The same with the config's faults applied.
ReversePdfs connection_reverse_pdfs(const scene::Scene& scene, const BidirVertex* light, int s,
                                    const BidirVertex* camera, int t, const MisConfig& config,
                                    const EdgeMedia* edge = nullptr);

// Weight of strategy (s, t) (s + t >= 2, t >= 1) for the path y_0..y_{s-1} z_{t-1}..z_0.
// For s = 0, camera[t-1] must lie on an area emitter.
float mis_weight(const scene::Scene& scene, const BidirVertex* light, int s, const BidirVertex* camera, int t,
                 const MisConfig& config);
// The same with the connection's reverse densities given (computed once and shared by
// several heuristics, or by a shifted path whose connection neighbourhood is the base's).
float mis_weight(const BidirVertex* light, int s, const BidirVertex* camera, int t, const MisConfig& config,
                 const ReversePdfs& reverse);

}  // namespace dp::pathspace
