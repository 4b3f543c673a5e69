// Generalized half-vector constraints of a specular chain, their 2x2 derivative
// blocks, the block-tridiagonal LU (tangent map), the determinant of the
// half-vector-preserving map and the generalized geometry term. All in double.
//
// Constraint at interior vertex i (Jakob & Marschner 2012, Sec. 4.1, Eq. 9/10):
//   h_i = eta_a w_a + eta_b w_b,  w_a = unit(x_{i-1} - x_i), w_b = unit(x_{i+1} - x_i),
//   eta_a / eta_b the indices on the sides of w_a / w_b (1 and 1 for reflection),
//   h^_i = sign(h_i . n) h_i / |h_i|   (oriented into the shading normal's hemisphere),
//   c_i = (h^_i . s, h^_i . t) - target_i.
// Index-matched refraction (eta = 1) has no normalized half vector: it is rejected.
// Blocks (J&M 2012, Sec. 4.2 and Appendix): a_i = dc_i / d(u,v)_{i-1},
// b_i = dc_i / d(u,v)_i (includes the shading-frame derivatives ds, dt built from dn/du,
// dn/dv), c_i = dc_i / d(u,v)_{i+1}; (u, v) are lengths along each vertex's (T1, T2).
#pragma once

#include <vector>

#include "manifold/chain.h"

namespace dp::manifold {

struct HalfVector {
  Vec3d h_hat{0, 0, 1};
  double h_len = 0;
  double sigma = 1;  // orientation sign applied to h / |h|
  double eta_a = 1, eta_b = 1;
  Vec3d w_a{0, 0, 1}, w_b{0, 0, 1};
  double d_a = 0, d_b = 0;  // segment lengths (d_a = inf for a pinned direction)
};

// Evaluates the generalized half vector at interior vertex i (1 <= i <= n-1).
WalkStatus half_vector(const Chain& chain, int i, HalfVector& out);
// Projected half vector (h^ . s, h^ . t) at interior vertex i (the constraint value
// before subtracting the target).
WalkStatus projected_half_vector(const Chain& chain, int i, Vec2d& out);
// Sets every interior vertex's target to its current projected half vector (glossy
// chains whose half vectors a walk must preserve).
WalkStatus set_targets_from_current(Chain& chain);

struct Blocks {
  std::vector<Mat2d> a, b, c;  // indexed by vertex i (entries 0 and n unused)
};
WalkStatus derivative_blocks(const Chain& chain, Blocks& out);

// Tangent map: T[i] (i = 1..n-1) with dx_i = T[i] dx_n for displacements of the end
// along its (T1, T2), keeping every constraint fixed. Block LU (J&M 2012, Sec. 4.2):
//   D_1 = b_1, U_i = D_i^-1 c_i, D_i = b_i - a_i U_{i-1}; T_{n-1} = -U_{n-1},
//   T_i = -U_i T_{i+1}. A singular D_i means the chain is not a manifold there.
WalkStatus tangent_map(const Chain& chain, std::vector<Mat2d>& T);

// det(dC / dx_interior) = prod det D_i (signed), the Jacobian determinant of the map
// from interior vertex positions (area, orthonormal tangent coordinates) to projected
// half vectors with both ends fixed (J&M 2012 Sec. 4.3; Kaplanyan et al. 2014). The
// half-vector-preserving map x -> x~ has |dx~/dx| = |det(x)| / |det(x~)|.
WalkStatus constraint_determinant(const Chain& chain, double& det);

// Generalized geometry term G(x_0 <-> x_n) of the chain (J&M 2012, Sec. 4.3):
//   G = |det T_1| |cos theta_0| |cos theta_1| / |x_1 - x_0|^2   (pinned position;
//       cos theta_0 only if x_0 has a surface), i.e. projected solid angle at x_0 per
//       unit area at x_n;
//   G = |det T_1| |cos theta_1|   (pinned direction: area perpendicular to the
//       direction per unit area at x_n).
// Cosines are taken with the geometric normals. Symmetric: G(x_0<->x_n) = G(x_n<->x_0).
WalkStatus generalized_geometry(const Chain& chain, double& G);

// Largest |c_i - target_i| over the interior (constraint residual).
double constraint_residual(const Chain& chain);

}  // namespace dp::manifold
