#include "gradients/volume_photon_shift.h"

namespace dp::gradients {

PhotonShift mixed_photon_shift(const Vec3& b, const Vec3& d, const Vec3& d_offset, float r, PhotonShiftFault fault) {
  PhotonShift out;
  out.kind = mixed_photon_shift_t(b, d, d_offset, r, out.b, fault);
  return out;
}

}  // namespace dp::gradients
