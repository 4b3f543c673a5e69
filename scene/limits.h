// Magnitude limit of the numbers a scene may hold (issue 18). Embree asserts that ray
// origins stay within ~1.8e18 (its FLT_LARGE), and at 1e12 float spacing is already
// 6.5e4 scene units, so nothing meaningful lies beyond it: every number read from a
// scene file (YAML or Mitsuba XML: coordinates, radii, scales, matrix entries, colours,
// ...) and every world-space vertex, sphere center and radius after its transform must
// be within +-kMaxSceneMagnitude; the loaders report anything larger as a file:line
// ValueError.
#pragma once

#include <cmath>

#include "core/math.h"

namespace dp::scene {

constexpr double kMaxSceneMagnitude = 1e12;
inline constexpr const char* kMaxSceneMagnitudeText = "1e12";

inline bool within_scene_limit(double v) { return std::abs(v) <= kMaxSceneMagnitude; }  // false for NaN
inline bool within_scene_limit(const Vec3& p) {
  return within_scene_limit(p.x()) && within_scene_limit(p.y()) && within_scene_limit(p.z());
}

}  // namespace dp::scene
