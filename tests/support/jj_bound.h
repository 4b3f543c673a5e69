// First-order per-sample bound on |J(x) J^-1(T(x)) - 1| for shift bijectivity tests
// (test_bijectivity.cpp, test_manifold_shift.cpp, test_gbdpt_shift.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/math.h"

namespace dp::test {

// Per-sample bound on |J(x) J^-1(T(x)) - 1| (first order), shared with
// test_manifold_shift.cpp. With T^-1(T(x)) = x exactly, both Jacobians would be computed
// from the same vertices and multiply to 1 up to double round-off (1e-15, floor 1e-12).
// They are not: the reverse shift re-traces x' in float, and both read float data.
//  * Each factor of J (jacobians.h) is a ratio of squared distances, cosines |n.w| and
//    half-vector products |w.h|. Moving vertex k by e_k turns the directions at it by
//    e_k / d_k (d_k: its shorter adjacent segment): the squared distances of its two
//    segments change by 2 e_k / d_k each (relative), the up to four cosines at the ends of
//    those segments and its half-vector product by e_k / (d_k c_k) each (c_k: the
//    smallest of them): at most 9 e_k / (d_k c_k) in ln J.
//  * e_k = |x'_k - x_k| (measured) + the float rounding of x_k's position and of its
//    direction over d_k, 2^-24 (|x_k|_inf + d_k), twice (base and re-traced).
//  * A Dirac vertex with curvature kappa_k (a sphere: 1 / r) turns a position error
//    into twice the normal's angle, 2 kappa_k e, in the reflected (refracted: at most as
//    much for eta < 2) direction; over the next segment l_k the later vertices move by
//    2 kappa_k l_k e more: the bound is multiplied by prod (1 + 2 kappa_k l_k) over the
//    path's Dirac vertices (manifold walks solve such chains).
// One vertex p (moved by e) with the segments to `ends`; c: the smallest |cos| of the
// segments against the normals at both of their ends and `c_extra` (|w.h|, or 1).
inline double jj_vertex_term(double e, const Vec3d& p, const Vec3d& n,
                             const std::vector<std::pair<Vec3d, Vec3d>>& ends, double c_extra) {
  double d = 1e300, c = std::min(1.0, c_extra);
  for (const auto& [q, nq] : ends) {
    const Vec3d w = (q - p).normalized();
    d = std::min(d, (q - p).norm());
    c = std::min(c, std::abs(n.dot(w)));
    if (nq != Vec3d::Zero()) c = std::min(c, std::abs(nq.dot(w)));
  }
  const double rounding = 2 * std::ldexp(1.0, -24) * (p.cwiseAbs().maxCoeff() + d);
  return 9 * (e + rounding) / (d * c);
}

}  // namespace dp::test
