// Sampling warps from [0,1)^2 to common domains, each with its pdf and its inverse
// (the inverse maps a point of the domain back to the unit square; round trips are
// tested in tests/core/test_warp.cpp). pdfs are w.r.t. the natural measure of the
// target domain: area on disk/triangle (barycentric), solid angle on sphere/hemisphere.
#pragma once

#include "core/math.h"

namespace dp::core::warp {

// Uniform on the unit disk, Shirley-Chiu concentric map.
Vec2 square_to_uniform_disk_concentric(const Vec2& u);
Vec2 uniform_disk_concentric_to_square(const Vec2& p);
inline float square_to_uniform_disk_pdf() { return kInvPi; }

// Cosine-weighted hemisphere around +z (via the concentric disk).
Vec3 square_to_cosine_hemisphere(const Vec2& u);
Vec2 cosine_hemisphere_to_square(const Vec3& w);
inline float square_to_cosine_hemisphere_pdf(const Vec3& w) { return w.z() > 0 ? w.z() * kInvPi : 0.0f; }

// Uniform on the unit sphere.
Vec3 square_to_uniform_sphere(const Vec2& u);
Vec2 uniform_sphere_to_square(const Vec3& w);
inline float square_to_uniform_sphere_pdf() { return kInv4Pi; }

// Uniform on the upper hemisphere.
Vec3 square_to_uniform_hemisphere(const Vec2& u);
Vec2 uniform_hemisphere_to_square(const Vec3& w);
inline float square_to_uniform_hemisphere_pdf(const Vec3& w) { return w.z() > 0 ? kInv2Pi : 0.0f; }

// Uniform in the cone of directions around +z with cos(theta) >= cos_max.
Vec3 square_to_uniform_cone(const Vec2& u, float cos_max);
Vec2 uniform_cone_to_square(const Vec3& w, float cos_max);
float square_to_uniform_cone_pdf(const Vec3& w, float cos_max);

// Uniform on a triangle: returns barycentrics (b1, b2) of vertices 1 and 2
// (b0 = 1 - b1 - b2). pdf w.r.t. area is 1 / area.
inline Vec2 square_to_uniform_triangle(const Vec2& u) {  // inline: on the light-sampling path
  const float s = std::sqrt(u.x());
  return Vec2(1.0f - s, u.y() * s);
}
Vec2 uniform_triangle_to_square(const Vec2& b);

}  // namespace dp::core::warp
