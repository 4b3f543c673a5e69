// Affine transforms of shapes in the YAML format:
//   transform: {scale: [sx, sy, sz] | s, rotate: {axis: [x, y, z], angle: degrees},
//               translate: [tx, ty, tz]}
// Every key is optional; they are applied in the fixed order scale, then rotate, then
// translate, whatever order they are written in: p' = T + R (S p). Rotation is
// right-handed (counter-clockwise looking down the axis toward the origin). Normals are
// transformed by the inverse transpose of the linear part and re-normalized.
#pragma once

#include <yaml-cpp/yaml.h>

#include "core/math.h"
#include "scene/shapes/shape.h"
#include "scene/loaders/yaml/yaml_values.h"

namespace dp::scene::yaml {

struct Transform {
  Vec3 scale{1, 1, 1};
  Mat3 rotation = Mat3::Identity();
  Vec3 translation{0, 0, 0};

  Mat3 linear() const { return rotation * scale.asDiagonal(); }
  Vec3 point(const Vec3& p) const { return rotation * scale.cwiseProduct(p) + translation; }
  // Inverse transpose of R S is R S^-1 (R orthonormal, S diagonal).
  Vec3 normal(const Vec3& n) const { return (rotation * n.cwiseQuotient(scale)).normalized(); }
  bool mirrors() const { return scale.prod() < 0.0f; }
  bool is_identity() const;
};

// ParseError/ValueError (with the line) for unknown keys, bad types, a zero scale
// component, a zero rotation axis.
Transform parse_transform(const Context& ctx, const YAML::Node& node);

// Applies `xf` to a mesh in place (positions, normals). A mirroring transform
// (negative determinant) also reverses the triangle winding so the geometric normal
// (v1 - v0) x (v2 - v0) stays on the side the transformed shading normals point to.
void apply_transform(const Transform& xf, TriangleMesh& mesh);

}  // namespace dp::scene::yaml
