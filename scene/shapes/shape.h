// Geometry. Shapes are baked into world space at load time (transforms applied).
// Triangle meshes are intersected by Embree's triangle geometry; spheres by an Embree
// user geometry evaluated in double. Quads are stored as two-triangle meshes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/warp.h"
#include "scene/surface.h"

namespace dp::scene {

enum class ShapeKind { mesh, sphere };

class Shape {
 public:
  virtual ~Shape() = default;
  virtual ShapeKind kind() const = 0;
  virtual float area() const = 0;
  virtual Bounds3 bounds() const = 0;
  // Uniform by area over the whole shape: pdf_area = 1 / area().
  virtual PositionSample sample_area(const Vec2& u) const = 0;
  // Fills the surface point for primitive `prim` at hit barycentrics/parameters (b1, b2)
  // of the ray hit (meshes: barycentrics of vertices 1, 2; spheres: ignored, p used).
  virtual void fill_surface(int prim, const Vec2& b, const Ray& ray, float t, SurfacePoint& out) const = 0;

  int material = -1;  // index into Scene::bsdfs(), -1 = none
  int emitter = -1;   // index into Scene::emitters(), -1 = not emissive
  int interior_medium = -1, exterior_medium = -1;
  std::string name;
};

class TriangleMesh final : public Shape {
 public:
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // per vertex, optional (empty = flat shading)
  std::vector<Vec2> uvs;      // per vertex, optional
  std::vector<std::array<uint32_t, 3>> triangles;
  bool smooth = true;         // interpolate vertex normals when present
  size_t degenerate_skipped = 0;

  // Removes zero-area / non-finite triangles (counted in degenerate_skipped), builds
  // the area CDF and the per-triangle frames. Call once after filling the arrays (and
  // again after changing them).
  void finalize();
  ShapeKind kind() const override { return ShapeKind::mesh; }
  float area() const override { return m_area; }
  Bounds3 bounds() const override;
  PositionSample sample_area(const Vec2& u) const override;
  // The body of sample_area(), inline for a caller that knows it holds a mesh (the area
  // emitter's next-event sampling: no virtual call, and the sample stays in registers
  // instead of a round trip through memory). Same arithmetic, same result.
  [[gnu::always_inline]] inline PositionSample sample_area_inline(const Vec2& u) const;
  void fill_surface(int prim, const Vec2& b, const Ray& ray, float t, SurfacePoint& out) const override;
  float triangle_area(size_t i) const;

 private:
  // Per-triangle constants (a hit only interpolates): the unit geometric normal, dp/du
  // and dp/dv from the uv parameterization (or an orthonormal tangent pair when the uvs
  // are degenerate), and the flat-shading frame. Costs 52 bytes per triangle and saves
  // the divisions and square roots of every hit.
  struct TriangleFrame {
    Vec3 ng, dpdu, dpdv;
    Frame flat;
    bool uv_ok = false;
  };
  TriangleFrame compute_frame(size_t i) const;
  std::vector<float> m_cdf;     // cumulative triangle areas, normalized
  std::vector<float> m_cdf_lo;  // m_cdf shifted by one: the lower end of triangle i's cell
  std::vector<float> m_cdf_inv_width;  // 1 / (m_cdf[i] - m_cdf_lo[i]), 0 for an empty cell
  std::vector<TriangleFrame> m_frames;
  float m_area = 0;
};

class Sphere final : public Shape {
 public:
  Sphere(const Vec3& center, float radius) : m_center(center), m_radius(radius) {}
  ShapeKind kind() const override { return ShapeKind::sphere; }
  float area() const override { return 4.0f * kPi * m_radius * m_radius; }
  Bounds3 bounds() const override;
  PositionSample sample_area(const Vec2& u) const override;
  void fill_surface(int prim, const Vec2& b, const Ray& ray, float t, SurfacePoint& out) const override;
  // Nearest intersection in (tmin, tmax), computed in double. Returns false if none.
  bool intersect(const Ray& ray, float& t) const;
  const Vec3& center() const { return m_center; }
  float radius() const { return m_radius; }
  bool flip_normals = false;  // normals point inward (Mitsuba flip_normals)

 private:
  Vec3 m_center;
  float m_radius;
};

using ShapePtr = std::unique_ptr<Shape>;

namespace detail {
// std::upper_bound (first index with cdf[i] > u, or cdf.size()) without data-dependent
// branches: light sampling draws u uniformly, so the comparisons of a branchy binary
// search are mispredicted half of the time (a quad light's two-entry CDF cost more in
// mispredictions than in arithmetic). The answer is always in [base, base + n]; the
// loop count depends only on the size.
inline size_t upper_bound_branchless(const std::vector<float>& cdf, float u) {
  const float* base = cdf.data();
  size_t n = cdf.size();
  while (n > 1) {
    const size_t half = n / 2;
    base += size_t(base[half - 1] <= u) * half;  // arithmetic, so no branch is emitted
    n -= half;
  }
  return size_t(base - cdf.data()) + (*base <= u ? 1 : 0);
}
}  // namespace detail

// Requires a finalized, non-empty mesh, i.e. area() > 0 (sample_area() checks with
// DP_CHECK; the area emitter tests area() before calling this).
[[gnu::always_inline]] inline PositionSample TriangleMesh::sample_area_inline(const Vec2& u) const {
  // Pick a triangle with probability area_i / area and reuse u.x within its CDF cell.
  const size_t i = std::min(detail::upper_bound_branchless(m_cdf, u.x()), m_cdf.size() - 1);
  // Rescale u.x to [0, 1) within the cell: (u - lo) / width, the division precomputed
  // (it sat on the light-sampling dependency chain); 0.5 for an empty cell.
  const float lo = m_cdf_lo[i];  // cdf[i - 1], 0 for i = 0 (no branch on the random index)
  const float inv_width = m_cdf_inv_width[i];
  const float ux = inv_width > 0 ? std::clamp((u.x() - lo) * inv_width, 0.0f, std::nextafter(1.0f, 0.0f)) : 0.5f;
  const Vec2 b = core::warp::square_to_uniform_triangle(Vec2(ux, u.y()));
  const auto& tri = triangles[i];
  const Vec3& v0 = positions[tri[0]];
  const Vec3& v1 = positions[tri[1]];
  const Vec3& v2 = positions[tri[2]];
  PositionSample s;
  const float b0 = 1.0f - b.x() - b.y();
  s.p = b0 * v0 + b.x() * v1 + b.y() * v2;
  s.n = m_frames[i].ng;  // = normalize((v1 - v0) x (v2 - v0)), precomputed
  s.uv = uvs.empty() ? b : Vec2(b0 * uvs[tri[0]] + b.x() * uvs[tri[1]] + b.y() * uvs[tri[2]]);
  s.pdf_area = 1.0f / m_area;
  return s;
}

}  // namespace dp::scene
