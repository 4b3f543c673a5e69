// A local chart of unit directions around `w` for finite-difference Jacobian tests:
// at(a, b) = normalize(w + a s + b t), coords() its inverse to first order.
#pragma once

#include <Eigen/Dense>
#include <cmath>

#include "core/math.h"

namespace dp::test {

struct DirectionChart {
  Vec3d w, s, t;
  explicit DirectionChart(const Vec3d& dir) : w(dir.normalized()) {
    const Vec3d a = std::abs(w.x()) > 0.9 ? Vec3d(0, 1, 0) : Vec3d(1, 0, 0);
    s = w.cross(a).normalized();
    t = w.cross(s);
  }
  Vec3d at(double a, double b) const { return (w + a * s + b * t).normalized(); }
  Eigen::Vector2d coords(const Vec3d& v) const { return {v.normalized().dot(s), v.normalized().dot(t)}; }
};

}  // namespace dp::test
