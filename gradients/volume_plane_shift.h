// The shift of gradient-domain photon planes (G-Plane; Gruson et al. 2018, Sec. 5.3,
// Fig. 6f). A photon plane {a0 + t0 w0 + t1 w1} (integrators/media_photons/photon_plane.h)
// meets the base camera ray c + w d at (t0, t1, w); the offset
//  * copies the camera distance, w' = w, onto the offset camera ray: d' = c' + w d';
//  * takes the photon at the gather point, b' = d' (a 0D kernel);
//  * keeps a0 and the light segment (a0, w0) and rotates the plane about that segment's
//    line until it holds d' (Sec. 5.3: "rotating the base plane by moving a2 to a2'"):
//    w1' keeps w1's angle theta to w0 and points from the axis toward d', so
//      t1' = rho' / sin(theta),  t0' = alpha' - t1' cos(theta),
//    alpha' = (d' - a0) . w0, rho' the distance of d' from the axis. The scattering point
//    a1' = a0 + t0' w0 moves along the segment; the shift fails where it leaves the
//    segment (t0' outside its range; the paper's "t0' negative") or the plane degenerates
//    (theta 0 or pi, d' on the axis). The inverse is the same rotation from d' back to d.
//    No reconnection: neither a0 nor the light segment changes; the phase at a1 keeps its
//    angle, so rho(w0, w1') = rho(w0, w1) and the phase sample's density is unchanged.
// Jacobian, in the estimator's measure: the plane estimate samples the raster position
// and w1 (solid angle) and integrates (t0, t1, w) against the 3D delta
// (integrators/plane/plane_gather.h), f = F / |det[w0, w1, d]|. At a fixed raster, w1 <->
// (t0, w) with dw1 = |det[w0, w1, d]| / t1^2 dt0 dw (the two tangents of w1 = (d(w) - a1(t0))
// / t1 span |w1 . (d x w0)| / t1^2), and in (t0, w) the shift is w' = w, t0' = alpha'(w) -
// rho'(w) cot(theta(t0, w)) with d t0'/d t0 = rho' / rho = t1' / t1. So
//   |dw1' / dw1| = |det[w0, w1', d']| / |det[w0, w1, d]| * t1 / t1'.
// Eq. 18 of the paper prints t0'/t0 * t1'/t1 * w0.(w1' x wc') / w0.(w1 x wc): the same
// determinant ratio, but its t-factors are not this measure's (central differences in
// test_volume_plane_shift.cpp reject them; PlaneShiftFault::paper_eq18).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace dp::gradients {

// Deliberate defect for the tests: the Jacobian with Eq. 18's printed t-factors
// (t0'/t0 t1'/t1) in place of t1/t1'.
enum class PlaneShiftFault : uint8_t { none, paper_eq18 };

template <class S>
struct PlaneRotation {
  Eigen::Matrix<S, 3, 1> w1{0, 0, 1};  // the offset plane's second direction w1'
  S t0 = 0, t1 = 0;                      // d' = a0 + t0 w0 + t1 w1'
};

// Rotates the plane (a0; w0, w1) about the line a0 + t w0 until it holds x (w0, w1 unit).
// False if the plane or the target is degenerate (sin(theta) or rho below 1e-9 relative).
template <class S>
bool rotate_plane_to(const Eigen::Matrix<S, 3, 1>& a0, const Eigen::Matrix<S, 3, 1>& w0,
                     const Eigen::Matrix<S, 3, 1>& w1, const Eigen::Matrix<S, 3, 1>& x, PlaneRotation<S>& out) {
  const S cos_t = w0.dot(w1), sin_t = w0.cross(w1).norm();
  const Eigen::Matrix<S, 3, 1> rel = x - a0;
  const S alpha = rel.dot(w0);
  const Eigen::Matrix<S, 3, 1> u = rel - alpha * w0;
  const S rho = u.norm();
  if (!(sin_t > S(1e-9)) || !(rho > S(1e-9) * rel.norm())) return false;
  out.w1 = cos_t * w0 + (sin_t / rho) * u;
  out.t1 = rho / sin_t;
  out.t0 = alpha - out.t1 * cos_t;
  return std::isfinite(double(out.t0)) && std::isfinite(double(out.t1));
}

// Solves a0 + t0 w0 + t1 w1 = c + w d by Cramer's rule (Moller & Trumbore's triple
// products; det = w0 . (d x w1) = -det[w0, w1, d]); false when |det| < 1e-12
// (the ray parallel to the plane). inv_det = 1 / |det[w0, w1, d]|.
template <class S>
bool plane_ray_solve(const Eigen::Matrix<S, 3, 1>& a0, const Eigen::Matrix<S, 3, 1>& w0,
                     const Eigen::Matrix<S, 3, 1>& w1, const Eigen::Matrix<S, 3, 1>& c,
                     const Eigen::Matrix<S, 3, 1>& d, S& t0, S& t1, S& w, S& inv_det) {
  const Eigen::Matrix<S, 3, 1> p = d.cross(w1);
  const S det = w0.dot(p);
  if (!(std::abs(det) > S(1e-12))) return false;
  const S inv = S(1) / det;
  const Eigen::Matrix<S, 3, 1> s = c - a0;
  const Eigen::Matrix<S, 3, 1> q = s.cross(w0);
  t0 = s.dot(p) * inv;
  t1 = d.dot(q) * inv;
  w = w1.dot(q) * inv;
  inv_det = std::abs(inv);
  return true;
}

// |det[w0, w1, d]| (the plane estimate's 3D delta, plane_gather.h).
template <class S>
S plane_det(const Eigen::Matrix<S, 3, 1>& w0, const Eigen::Matrix<S, 3, 1>& w1, const Eigen::Matrix<S, 3, 1>& d) {
  return std::abs(w0.dot(w1.cross(d)));
}

// |dw1'/dw1| of the shift (header comment): base (w1, camera direction d, t0, t1), offset
// (w1', d', t0', t1').
template <class S>
S plane_shift_jacobian(const Eigen::Matrix<S, 3, 1>& w0, const Eigen::Matrix<S, 3, 1>& w1,
                       const Eigen::Matrix<S, 3, 1>& d, S t0, S t1, const Eigen::Matrix<S, 3, 1>& w1_off,
                       const Eigen::Matrix<S, 3, 1>& d_off, S t0_off, S t1_off,
                       PlaneShiftFault fault = PlaneShiftFault::none) {
  const S det = plane_det(w0, w1, d), det_off = plane_det(w0, w1_off, d_off);
  const S t_factor = fault == PlaneShiftFault::paper_eq18 ? (t0_off / t0) * (t1_off / t1) : t1 / t1_off;
  return det_off / det * t_factor;
}

}  // namespace dp::gradients
