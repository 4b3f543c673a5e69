#include "core/warp.h"

namespace dp::core::warp {

Vec2 square_to_uniform_disk_concentric(const Vec2& u) {
  const float x = 2.0f * u.x() - 1.0f, y = 2.0f * u.y() - 1.0f;
  if (x == 0.0f && y == 0.0f) return Vec2(0, 0);
  float r, phi;
  if (std::abs(x) > std::abs(y)) {
    r = x;
    phi = (kPi / 4.0f) * (y / x);
  } else {
    r = y;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (x / y);
  }
  return Vec2(r * std::cos(phi), r * std::sin(phi));
}

Vec2 uniform_disk_concentric_to_square(const Vec2& p) {
  const float r = std::sqrt(p.x() * p.x() + p.y() * p.y());
  if (r == 0.0f) return Vec2(0.5f, 0.5f);
  float phi = std::atan2(p.y(), p.x());
  if (phi < -kPi / 4.0f) phi += 2.0f * kPi;  // phi in [-pi/4, 7pi/4)
  float x, y;
  if (phi < kPi / 4.0f) {  // region 1: x = r
    x = r;
    y = phi * r / (kPi / 4.0f);
  } else if (phi < 3.0f * kPi / 4.0f) {  // region 2: y = r
    y = r;
    x = -(phi - kPi / 2.0f) * r / (kPi / 4.0f);
  } else if (phi < 5.0f * kPi / 4.0f) {  // region 3: x = -r
    x = -r;
    y = -(phi - kPi) * r / (kPi / 4.0f);
  } else {  // region 4: y = -r
    y = -r;
    x = (phi - 3.0f * kPi / 2.0f) * r / (kPi / 4.0f);
  }
  return Vec2(0.5f * (x + 1.0f), 0.5f * (y + 1.0f));
}

Vec3 square_to_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = square_to_uniform_disk_concentric(u);
  const float z = safe_sqrt(1.0f - d.squaredNorm());
  return Vec3(d.x(), d.y(), z);
}

Vec2 cosine_hemisphere_to_square(const Vec3& w) { return uniform_disk_concentric_to_square(Vec2(w.x(), w.y())); }

Vec3 square_to_uniform_sphere(const Vec2& u) {
  const float z = 1.0f - 2.0f * u.y();
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.x();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

namespace {
float phi_to_unit(float x, float y) {
  float phi = std::atan2(y, x);
  if (phi < 0) phi += 2.0f * kPi;
  return std::min(phi * kInv2Pi, std::nextafter(1.0f, 0.0f));
}
}  // namespace

Vec2 uniform_sphere_to_square(const Vec3& w) { return Vec2(phi_to_unit(w.x(), w.y()), 0.5f * (1.0f - w.z())); }

Vec3 square_to_uniform_hemisphere(const Vec2& u) {
  const float z = u.y();
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.x();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec2 uniform_hemisphere_to_square(const Vec3& w) { return Vec2(phi_to_unit(w.x(), w.y()), w.z()); }

Vec3 square_to_uniform_cone(const Vec2& u, float cos_max) {
  const float z = 1.0f - u.y() * (1.0f - cos_max);
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.x();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec2 uniform_cone_to_square(const Vec3& w, float cos_max) {
  return Vec2(phi_to_unit(w.x(), w.y()), (1.0f - w.z()) / (1.0f - cos_max));
}

float square_to_uniform_cone_pdf(const Vec3& w, float cos_max) {
  return w.z() >= cos_max ? 1.0f / (2.0f * kPi * (1.0f - cos_max)) : 0.0f;
}

// Heitz 2019-style low-distortion mapping is not invertible in closed form as
// simply; use the classic sqrt mapping b1 = 1 - sqrt(u1), b2 = u2 sqrt(u1).
Vec2 uniform_triangle_to_square(const Vec2& b) {
  const float s = 1.0f - b.x();
  const float u1 = s * s;
  const float u2 = s > 0 ? b.y() / s : 0.0f;
  return Vec2(u1, u2);
}

}  // namespace dp::core::warp
