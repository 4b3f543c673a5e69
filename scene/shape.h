// Geometry. Shapes are baked into world space at load time (transforms applied).
// Triangle meshes are intersected by Embree's triangle geometry; spheres by an Embree
// user geometry evaluated in double. Quads are stored as two-triangle meshes.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
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
  std::vector<float> m_cdf;  // cumulative triangle areas, normalized
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

}  // namespace dp::scene
