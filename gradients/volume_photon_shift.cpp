#include "gradients/volume_photon_shift.h"

namespace dp::gradients {

PhotonShift mixed_photon_shift(const Vec3& b, const Vec3& d, const Vec3& d_offset, float r, PhotonShiftFault fault) {
  const float r2 = r * r;
  PhotonShift out;
  if ((b - d_offset).squaredNorm() <= r2) {  // in both kernels: the null shift
    out.b = b;
    out.kind = PhotonShiftKind::null;
    return out;
  }
  const Vec3 delta = d_offset - d;
  const Vec3 b_star = b + delta;  // the simple shift
  if ((b_star - d).squaredNorm() > r2) {
    out.b = b_star;
    out.kind = PhotonShiftKind::simple;
    return out;
  }
  // b* fell into the overlap: reflect it across the plane through d' normal to u (Eq. 16).
  const Vec3 u = delta.normalized();
  const float k = fault == PhotonShiftFault::half_reflection ? 1.0f : 2.0f;
  out.b = b_star + k * u.dot(d_offset - b_star) * u;
  out.kind = PhotonShiftKind::reflected;
  return out;
}

}  // namespace dp::gradients
