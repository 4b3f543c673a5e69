// Multiple importance sampling of vertex connection and merging (Georgiev et al. 2012,
// "Light transport simulation with vertex connection and merging"; the recursive
// formulation of their technical report "Implementing vertex connection and merging",
// Eqs. 31-43) in the area-density form of bidir_vertex.h, so that the weight of any
// connection or merge costs O(1) once each subpath has its prefix quantities.
//
// Strategies of a path x_0 .. x_k (light end first), as in bidir_mis.h plus merging:
//  * connection (s, t): density p_s = prod_{i<s} p->(x_i) prod_{i>=s} p<-(x_i);
//  * merge at x_j (a light subpath y_0 .. y_j and a camera subpath ending at x_j, both
//    sampled): p_VM,j = p_j * p->(x_j) * eta, eta = pi r^2 N (N light paths per
//    iteration: merging uses every light path, connection one; Georgiev et al. 2012,
//    Eq. 10-11). Possible at surface vertices whose path lobe is not Dirac, 1 <= j,
//    never at the pinhole or on a light endpoint.
//  weight = p^b / sum over enabled strategies of p_i^b (b = 1 balance, 2 power).
//
// Prefix quantities. For the vertices v_0 .. v_i of one subpath (light or camera
// order) let D_i = sum over enabled strategies in which the OTHER side generated v_i and
// more (connections and merges), each as (p / p_i)^b / p->(v_i)^b, where p_i is the
// connection strategy ending at v_i. Then
//   D_i = a_i + b_i * h(p<-(v_{i-1})),
//   a_i = h(1 / p->(v_i)) [connection v_{i-1}--v_i possible]
//   b_i = h(1 / p->(v_i)) (V [merge at v_{i-1}] + I_{i-1}),   V = h(eta) (0: no merging)
//   I_i = D_i with v_i an interior vertex (its a_i term dropped if its lobe is Dirac),
// h(x) = x^b, and p<-(v_{i-1}) is the only factor that depends on where the path
// continues after v_i: it is stored for interior vertices and recomputed at a connection
// or merge (this split is the dVCM / dVC pair of the technical report; dVM = dVC/eta).
// Weights:
//   connection (s, t): 1 / (1 + W_L + W_C), W_L = h(p<-(y_{s-1})) (V [merge at y_{s-1}] + D^L_{s-1}),
//                       W_C = h(p<-(z_{t-1})) (V [merge at z_{t-1}] + D^C_{t-1});
//   merge at (y_j ~ z_{t-1}): 1 / (1 + (D^L_j + D^C_{t-1}) / V).
// (With the adaptive kernel below, each V is h(eta_k) of the vertex it merges at.)
// Dirac-derived densities are 0 in storage and count as 1 (they cancel), as in bidir_mis.
//
// Adaptive merging kernel (Sun et al. 2017, Sec. 6; VcmMisConfig::adaptive_kernel): the
// radius at camera vertex z_t is r_t = 0.5^(10 tau(z_(t-1))) r_(t-1), so a merge at x_k
// has eta_k = eta * prod c(x_m) over the vertices between x_k and the pinhole, with
// c(v) = r_t^2 / r_(t-1)^2 = 0.25^(10 tau(v)), tau = min(1, roughness) (diffuse 1; 0 where
// the path took a Dirac lobe; vcm_kernel_shrink). eta_k is a function of the path, so the weights stay a partition of
// unity. On the camera side it is known per vertex: m_i = prod_{q=1..i} c(v_q) (camera
// order, the pinhole v_0 has m = 1) and a merge at v_{i-1} uses eta * m_(i-2). On the light
// side the product is only complete once the camera side is known: the prefix keeps the
// merge-derived part of b apart, m_i = sum over merges at y_q (q < i) carrying
// prod c(y_(q+1) .. y_(i-1)), extended by h(c(v_(i-1))) per step; at evaluation it is
// scaled by K = h(c(junction) * prod c(camera vertices)):
//   D_i = a_i + (b_i + K m_i) h(p<-(v_(i-1))).
// Without the adaptive kernel every c is 1 and this is the single-eta recursion above.
#pragma once

#include <cstdint>

#include "pathspace/bidir_mis.h"

namespace dp::pathspace {

// Deliberate defects the tests must reject (tests/integrators/test_vcm_mis.cpp). C++ only.
enum class VcmFault : uint8_t {
  none,
  merge_without_light_prefix,  // a merge's light-side sum keeps only the connection at the photon (b term lost)
  dirac_interior_kept,         // a connection ending at an interior Dirac vertex stays in the prefix sums
  shrink_light_side_lost,      // adaptive kernel: light-side merge terms without the camera side's shrink (K = 1)
};

struct VcmMisConfig {
  MisHeuristic heuristic = MisHeuristic::power;
  VcmFault fault = VcmFault::none;
  bool connections = true;  // vertex connection strategies (camera hits, light tracing, s,t >= 1)
  float eta = 0.0f;         // pi r^2 * light paths per iteration; 0 = no merging strategies
  // No merge at a vertex whose BSDF's roughness (lowest microfacet alpha of its non-Dirac
  // parts) is below this: near-specular surfaces are left to connections (Sun et al.
  // 2017 use 0.01 for G-VCM); 0 = merge at every non-Dirac vertex.
  float min_merge_roughness = 0.0f;
  // Shrink the merging radius along the camera subpath (Sun et al. 2017, Sec. 6; header).
  bool adaptive_kernel = false;
};

// Prefix quantities of one subpath vertex (header comment). Light order: D_i = a + (b + K m)
// h(p<-(v_{i-1})), b the connection-derived part, m the merge-derived part. Camera order:
// D_i = a + b h(p<-(v_{i-1})), m = prod_{q=1..i} c(v_q) (1 at the pinhole).
struct VcmPrefix {
  double a = 0.0, b = 0.0, m = 1.0;
};

// c(v) of the adaptive kernel: 0.25^(10 min(1, roughness)) at surface vertices the path
// leaves through a non-Dirac lobe, 1 elsewhere and without the adaptive kernel.
double vcm_kernel_shrink(const BidirVertex& v, const VcmMisConfig& config);

// Prefix quantities of every vertex of a subpath (light order for `camera_side` false,
// camera order otherwise): out[0 .. n-1].
void vcm_prefixes(const BidirVertex* path, int n, bool camera_side, const VcmMisConfig& config, VcmPrefix* out);

// Weight of connection (s, t) (s = 0: the camera walk hit a light at camera[t-1]; t = 1:
// light tracing), for subpaths with prefix arrays lp (light) and cp (camera).
float vcm_connection_weight(const scene::Scene& scene, const BidirVertex* light, const VcmPrefix* lp, int s,
                            const BidirVertex* camera, const VcmPrefix* cp, int t, const VcmMisConfig& config);

// What a merge needs of a light vertex y_j (j >= 1), compact for the photon grid: its
// direction toward y_{j-1}, its prefix quantities and the factor converting a solid-angle
// density leaving y_j toward y_{j-1} into y_{j-1}'s area density (solid_angle_to_area).
struct VcmPhotonMis {
  Vec3 wi{0, 0, 0};
  VcmPrefix prefix;
  float prev_area = 0;
};
VcmPhotonMis vcm_photon_mis(const BidirVertex* light, const VcmPrefix* lp, int j);

// Weight of merging the light vertex y_j (as `photon`) at camera vertex camera[t-1]
// (t >= 2). The path is evaluated at the camera vertex, arriving along the photon's wi.
float vcm_merge_weight(const VcmPhotonMis& photon, const BidirVertex* camera, const VcmPrefix* cp, int t,
                       const VcmMisConfig& config);
// The same for light[j] of a stored light path (tests).
inline float vcm_merge_weight(const BidirVertex* light, const VcmPrefix* lp, int j, const BidirVertex* camera,
                              const VcmPrefix* cp, int t, const VcmMisConfig& config) {
  return vcm_merge_weight(vcm_photon_mis(light, lp, j), camera, cp, t, config);
}

// Can a merge happen at this vertex (surface, BSDF with a non-Dirac part)? `interior`:
// the path continues through the vertex along its stored lobe (Dirac lobes excluded).
// `min_roughness`: VcmMisConfig::min_merge_roughness.
bool vcm_mergeable(const BidirVertex& v, bool interior, float min_roughness = 0.0f);

}  // namespace dp::pathspace
