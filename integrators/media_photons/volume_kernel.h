// Density-estimation kernels and the progressive radius schedule of the volumetric
// photon estimators (`vpm`, `bre`; Gruson et al. 2018, Sec. 3.1, Eq. 5: K in the density
// estimator D). Uniform kernels, as the paper uses for all its results (Sec. 6.1):
//  * 3D (point query, `vpm`): K3(x) = 1 / (4/3 pi r^3) for |x| <= r, a density in
//    volume measure (integrates to 1 over R^3);
//  * 2D (beam query, `bre`; Jarosz et al. 2008): K2(x) = 1 / (pi r^2) for |x| <= r, a
//    density over the plane across the camera beam. Any radially symmetric 3D kernel
//    integrated along a line at perpendicular distance d is a 2D kernel in d; the BRE
//    uses the uniform one directly.
// Point-Beam 3D (Gruson et al. 2018, Sec. 5.1; `bre` with kernel=3d, `gbre`): a photon
// b's 3D kernel meets the camera segment o + t w (w unit, t in [0, s]) along the chord of
// points within r of b, t in [t_p - h, t_p + h] with t_p = (b - o).w the projection,
// h = sqrt(r^2 - d_perp^2), clipped to [0, s]; the query integrates Tr(c, t) over it (or
// samples t uniformly in it, density 1 / length).
// Progressive radius (Knaus & Zwicker 2011, Sec. 4.3, for a D-dimensional kernel): the
// kernel's volume shrinks by (i + alpha) / (i + 1) per iteration,
//   r_{i+1}^D = r_i^D (i + alpha) / (i + 1),  i = 1, 2, ...,
// so r_i = r_1 [Gamma(i + alpha) / (Gamma(1 + alpha) Gamma(i + 1))]^(1/D) ~ i^((alpha-1)/D).
// Gruson et al. 2018, Sec. 6.1: alpha = 0.7.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace dp::integrators {

// Value of the uniform D-dimensional kernel (D = 2 or 3) of radius r inside its support.
double uniform_kernel(int dim, double r);
// Radius of 0-based iteration `index` (r_1 at index 0) for a D-dimensional kernel.
double progressive_radius(double r1, int64_t index, double alpha, int dim);

// The chord [lo, hi] of a photon at projection t_p and squared perpendicular distance d2
// from a segment of length s (may be +inf); false when it is empty (or of zero length).
inline bool point_beam_chord(float t_p, float d2, float r, float s, float& lo, float& hi) {
  const float h2 = r * r - d2;
  if (!(h2 >= 0.0f)) return false;
  const float h = std::sqrt(h2);
  lo = std::max(0.0f, t_p - h);
  hi = std::min(s, t_p + h);
  return hi > lo;
}
// The same from the positions: the photon b against the ray o + t w.
inline bool point_beam_chord(const Vec3& o, const Vec3& w, float s, const Vec3& b, float r, float& lo, float& hi) {
  const Vec3 v = b - o;
  const float t_p = v.dot(w);
  return point_beam_chord(t_p, std::max(0.0f, v.squaredNorm() - t_p * t_p), r, s, lo, hi);
}

}  // namespace dp::integrators
