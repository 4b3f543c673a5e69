#include "scene/media/equiangular.h"

#include <algorithm>
#include <cmath>

namespace dp::scene {

Equiangular equiangular_setup(const Vec3& o, const Vec3& d, float t_max, const Vec3& y) {
  Equiangular e;
  if (!(t_max > 0.0f)) return e;
  const Vec3d dd = d.cast<double>().normalized();
  const Vec3d oy = (y - o).cast<double>();
  e.delta = oy.dot(dd);
  e.h = (oy - e.delta * dd).norm();
  if (!(e.h > 0.0) || !std::isfinite(e.h) || !std::isfinite(e.delta)) return e;
  e.theta_a = std::atan2(-e.delta, e.h);
  e.theta_b = std::isfinite(t_max) ? std::atan2(double(t_max) - e.delta, e.h) : 0.5 * kPiD;
  e.ok = e.theta_b > e.theta_a;
  return e;
}

float equiangular_sample(const Equiangular& e, float t_max, float u) {
  const double theta = e.theta_a + double(u) * (e.theta_b - e.theta_a);
  const double t = e.delta + e.h * std::tan(theta);
  return float(std::clamp(t, 0.0, double(t_max)));
}

float equiangular_pdf(const Equiangular& e, float t_max, float t) {
  if (!e.ok || !(t >= 0.0f) || !(t <= t_max)) return 0.0f;
  const double s = double(t) - e.delta;
  return float(e.h / ((e.theta_b - e.theta_a) * (e.h * e.h + s * s)));
}

}  // namespace dp::scene
