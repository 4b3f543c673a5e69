// The kernel-space shifts of gradient-domain volumetric photon mapping (G-VPM; Gruson et
// al. 2018, Sec. 4.1-4.2). The first building block of `gvpm` (docs/gvpm_plan.md); the
// camera-prefix shift and the photon's reconnection are not here.
//  * Gather point (Sec. 4.1): the offset copies the base's sampled distance, t' = t
//    (Jacobian 1); it fails where the offset camera segment is shorter (Fig. 3).
//  * Photon (Sec. 4.2), base gather point d, offset gather point d', kernel radius r (the
//    same at both), base photon b with |b - d| <= r:
//      simple:  b' = b + (d' - d);
//      null:    b' = b (the photon is in both kernels: no reconnection needed);
//      mixed:   null inside the overlap of the two kernels, otherwise the simple shift
//               b* = b + (d' - d), reflected when b* falls in the overlap across the plane
//               through d' normal to u = (d' - d) / |d' - d|:
//                 b' = b* + 2 u^T (d' - b*) u                               (Eq. 16).
//    All three are rigid (Jacobian 1). The mixed shift maps the base kernel onto the
//    offset kernel and its inverse is the mixed shift from d' to d (a reflected b' lies
//    outside the base kernel, so the reverse shift takes the same branch back).
#pragma once

#include <cstdint>

#include "core/math.h"

namespace dp::gradients {

// The offset gather distance: t (copied) if t < the offset segment's length, else the
// shift fails (returns false).
inline bool shift_gather_distance(float t, float offset_segment, float& t_offset) {
  t_offset = t;
  return t < offset_segment;
}

enum class PhotonShiftKind : uint8_t { null, simple, reflected };

struct PhotonShift {
  Vec3 b{0, 0, 0};
  PhotonShiftKind kind = PhotonShiftKind::simple;
};

// Deliberate defect for the tests (test_volume_photon_shift.cpp): the reflection without
// its factor 2 (a projection onto the plane: not invertible).
enum class PhotonShiftFault : uint8_t { none, half_reflection };

// Eq. 16's mixed shift, generic in the vector type (Vec3 for the renderer, Vec3d for the
// tests' finite differences): writes b' into `out`, returns the branch taken.
template <class V, class S>
PhotonShiftKind mixed_photon_shift_t(const V& b, const V& d, const V& d_offset, S r, V& out,
                                     PhotonShiftFault fault = PhotonShiftFault::none) {
  const S r2 = r * r;
  if ((b - d_offset).squaredNorm() <= r2) {  // in both kernels: the null shift
    out = b;
    return PhotonShiftKind::null;
  }
  const V delta = d_offset - d;
  const V b_star = b + delta;  // the simple shift
  if ((b_star - d).squaredNorm() > r2) {
    out = b_star;
    return PhotonShiftKind::simple;
  }
  // b* fell into the overlap: reflect it across the plane through d' normal to u (Eq. 16).
  const V u = delta.normalized();
  const S k = fault == PhotonShiftFault::half_reflection ? S(1) : S(2);
  out = b_star + k * u.dot(d_offset - b_star) * u;
  return PhotonShiftKind::reflected;
}

// Eq. 16's mixed shift of base photon b (|b - d| <= r) from gather point d to d'.
PhotonShift mixed_photon_shift(const Vec3& b, const Vec3& d, const Vec3& d_offset, float r,
                               PhotonShiftFault fault = PhotonShiftFault::none);
// The simple shift b + (d' - d).
inline Vec3 simple_photon_shift(const Vec3& b, const Vec3& d, const Vec3& d_offset) { return b + (d_offset - d); }

}  // namespace dp::gradients
