// A point on a surface found by ray intersection or by sampling a shape.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace dp::scene {

class Bsdf;
class Emitter;

struct SurfacePoint {
  Vec3 p{0, 0, 0};
  Vec3 ng{0, 0, 1};  // geometric normal, unit; for meshes normalize((v1-v0)x(v2-v0))
  Frame shading;     // shading frame (interpolated normal if smooth), s along dp/du
  Vec2 uv{0, 0};
  Vec3 dpdu{1, 0, 0}, dpdv{0, 1, 0};
  Vec3 dndu{0, 0, 0}, dndv{0, 0, 0};  // shading-normal derivatives (0 for flat shading)
};

struct SurfaceHit : SurfacePoint {
  float t = 0;         // ray parameter
  int32_t shape = -1;  // index into Scene::shapes()
  int32_t prim = -1;   // triangle index within a mesh, 0 for analytic shapes
  const Bsdf* bsdf = nullptr;        // null for a pure emitter without material
  const Emitter* emitter = nullptr;  // area emitter attached to the shape, if any
  int32_t interior_medium = -1, exterior_medium = -1;
};

// A sampled position on a shape, with its area density.
struct PositionSample {
  Vec3 p{0, 0, 0};
  Vec3 n{0, 0, 1};  // geometric normal
  Vec2 uv{0, 0};
  float pdf_area = 0;
};

}  // namespace dp::scene
