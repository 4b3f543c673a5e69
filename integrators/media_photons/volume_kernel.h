// Density-estimation kernels and the progressive radius schedule of the volumetric
// photon estimators (`vpm`, `bre`; Gruson et al. 2018, Sec. 3.1, Eq. 5: K in the density
// estimator D). Uniform kernels, as the paper uses for all its results (Sec. 6.1):
//  * 3D (point query, `vpm`): K3(x) = 1 / (4/3 pi r^3) for |x| <= r, a density in
//    volume measure (integrates to 1 over R^3);
//  * 2D (beam query, `bre`; Jarosz et al. 2008): K2(x) = 1 / (pi r^2) for |x| <= r, a
//    density over the plane across the camera beam. Any radially symmetric 3D kernel
//    integrated along a line at perpendicular distance d is a 2D kernel in d; the BRE
//    uses the uniform one directly.
// Progressive radius (Knaus & Zwicker 2011, Sec. 4.3, for a D-dimensional kernel): the
// kernel's volume shrinks by (i + alpha) / (i + 1) per iteration,
//   r_{i+1}^D = r_i^D (i + alpha) / (i + 1),  i = 1, 2, ...,
// so r_i = r_1 [Gamma(i + alpha) / (Gamma(1 + alpha) Gamma(i + 1))]^(1/D) ~ i^((alpha-1)/D).
// Gruson et al. 2018, Sec. 6.1: alpha = 0.7.
#pragma once

#include <cstdint>

namespace dp::integrators {

// Value of the uniform D-dimensional kernel (D = 2 or 3) of radius r inside its support.
double uniform_kernel(int dim, double r);
// Radius of 0-based iteration `index` (r_1 at index 0) for a D-dimensional kernel.
double progressive_radius(double r1, int64_t index, double alpha, int dim);

}  // namespace dp::integrators
