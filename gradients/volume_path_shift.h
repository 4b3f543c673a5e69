// The geometric part of G-PT's shift through medium vertices (Gruson et al. 2018, Sec. 6
// "Gradient-domain Volumetric Path Tracing": half-vector copy / reconnection as Kettunen
// et al. 2015 plus a copy of the distance sampled on the base path, as Sec. 4.1).
//  * Distance copy: a base medium vertex x1 = o + t d on the primary ray becomes
//    x1' = o' + t d' on the offset's primary ray (t' = t, Sec. 4.1, Fig. 3). In the
//    sampling coordinates (raster position, t) the map is a translation: Jacobian 1.
//  * Reconnection from x1' (or x1 for the inverse) to the base's next vertex x2, which
//    stays put. In the sampling coordinates of the edge -- the direction w1 (solid angle)
//    and, for a medium end, the free-flight distance t2 -- the factor is
//      |d(w1', t2') / d(w1, t2)| = |x2 - x1|^2 / |x2 - x1'|^2                 (medium end)
//      |d w1' / d w1|           = |cos'| |x2 - x1|^2 / (|cos| |x2 - x1'|^2)  (surface end)
//    (the volume element t^2 dt dw and the area element d^2 / |cos| dw of Eq. 4: the
//    geometry term has no cosine at a medium vertex; Kettunen 2015, Eq. 11 at surfaces).
// The functions are generic in the vector type (Vec3 for the renderer, Vec3d for the
// tests' finite differences, tests/gradients/test_volume_path_shift.cpp).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace dp::gradients {

// A deliberate defect for the tests' negative controls: the reconnection factor reported
// as 1 (only ever set by C++ test code through GptFaults).
enum class VolumeShiftFault : uint8_t { none, unit_reconnection };

// x1' = o' + t d' (d' unit): the offset's medium vertex at the copied distance t.
template <class V, class S>
V copy_medium_distance_t(const V& offset_origin, const V& offset_dir, S t) {
  return offset_origin + t * offset_dir;
}

// The reconnection factor above; `target_normal` null for a medium end.
template <class V, class S>
S volume_reconnection_jacobian_t(const V& base_prev, const V& offset_prev, const V& target, const V* target_normal,
                                 VolumeShiftFault fault = VolumeShiftFault::none) {
  if (fault == VolumeShiftFault::unit_reconnection) return S(1);
  const V e = target - base_prev, e_off = target - offset_prev;
  const S d2 = e.squaredNorm(), d2_off = e_off.squaredNorm();
  if (!(d2_off > S(0))) return S(0);
  S J = d2 / d2_off;
  if (target_normal) {
    const S c = std::abs(target_normal->dot(e)) / std::sqrt(d2);
    const S c_off = std::abs(target_normal->dot(e_off)) / std::sqrt(d2_off);
    if (!(c > S(0))) return S(0);
    J *= c_off / c;
  }
  return J;
}

// The offset edge of a reconnection: the unit direction x1' -> x2 and its length.
template <class V, class S>
void volume_reconnection_edge_t(const V& offset_prev, const V& target, V& dir, S& length) {
  const V e = target - offset_prev;
  length = e.norm();
  dir = e / length;
}

inline double volume_reconnection_jacobian(const Vec3& base_prev, const Vec3& offset_prev, const Vec3& target,
                                           const Vec3* target_normal, VolumeShiftFault fault) {
  const Vec3d n = target_normal ? Vec3d(target_normal->cast<double>()) : Vec3d::Zero();
  return volume_reconnection_jacobian_t<Vec3d, double>(base_prev.cast<double>(), offset_prev.cast<double>(),
                                                       target.cast<double>(), target_normal ? &n : nullptr, fault);
}

}  // namespace dp::gradients
