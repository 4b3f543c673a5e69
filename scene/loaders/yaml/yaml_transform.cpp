#include "scene/loaders/yaml/yaml_transform.h"

#include <utility>

#include "core/error.h"

namespace dp::scene::yaml {

bool Transform::is_identity() const {
  return scale == Vec3(1, 1, 1) && rotation == Mat3::Identity() && translation == Vec3::Zero();
}

Transform parse_transform(const Context& ctx, const YAML::Node& node) {
  check_keys(ctx, node, {"scale", "rotate", "translate"}, "transform");
  Transform xf;
  if (const YAML::Node s = node["scale"]; s.IsDefined()) {
    xf.scale = s.IsScalar() ? Vec3::Constant(get_float(ctx, s, "scale")) : get_vec3(ctx, s, "scale");
    if ((xf.scale.array() == 0.0f).any()) value_error(ctx, s, "'scale' components must be non-zero");
  }
  if (const YAML::Node r = node["rotate"]; r.IsDefined()) {
    check_keys(ctx, r, {"axis", "angle"}, "rotate");
    const Vec3 axis = get_direction(ctx, require(ctx, r, "axis", "rotate"), "axis");
    const float angle = get_float(ctx, require(ctx, r, "angle", "rotate"), "angle");
    xf.rotation = Eigen::AngleAxisf(deg_to_rad(angle), axis).toRotationMatrix();
  }
  if (const YAML::Node t = node["translate"]; t.IsDefined()) xf.translation = get_vec3(ctx, t, "translate");
  return xf;
}

void apply_transform(const Transform& xf, TriangleMesh& mesh) {
  for (Vec3& p : mesh.positions) p = xf.point(p);
  for (Vec3& n : mesh.normals) n = xf.normal(n);
  if (xf.mirrors())
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
}

}  // namespace dp::scene::yaml
