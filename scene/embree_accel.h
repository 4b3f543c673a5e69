// Embree 3 acceleration structure behind Scene. The header is Embree-free; only
// embree_accel.cpp includes Embree. Triangle meshes become Embree triangle geometry,
// spheres user geometry (intersected in double by Sphere::intersect). Geometry id ==
// shape index.
#pragma once

#include <memory>
#include <vector>

#include "core/math.h"
#include "scene/shapes/shape.h"

namespace dp::scene {

struct RawHit {
  float t = kInfinity;
  int shape = -1;
  int prim = -1;
  Vec2 b{0, 0};  // barycentrics of vertices 1, 2 (meshes)
  Vec3 ng{0, 0, 1};  // Embree's unnormalized geometric normal (benchmarks only)
};

class EmbreeAccel {
 public:
  explicit EmbreeAccel(const std::vector<ShapePtr>& shapes);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;
  bool intersect(const Ray& ray, RawHit& hit) const;
  bool occluded(const Ray& ray) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace dp::scene
