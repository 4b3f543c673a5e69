// The `shapes:` section: a list of {type: mesh | triangle | quad | sphere, ...}.
// Keys common to every shape: material, emission (RGB radiance, front side only),
// interior, exterior (medium names), name, transform (yaml_transform.h).
//   mesh:     file (.obj/.ply, relative to the scene file), smooth (default true); a
//             smooth mesh whose file has no normals is offered to
//             LoadOptions::mesh_normals with its material (loader.h)
//   triangle: vertices [[x,y,z] x 3]            uv (0,0), (1,0), (0,1)
//   quad:     vertices [[x,y,z] x 4], planar and in order (convex, no bow-tie);
//             split into (v0,v1,v2), (v0,v2,v3);  uv (0,0), (1,0), (1,1), (0,1)
//   sphere:   center, radius > 0; a transform may only scale uniformly (rotation
//             moves the center; the sphere's uv parameterization stays world-aligned)
// A shape without emission needs a material; `material: none` (only with interior or
// exterior) is an index-matched medium boundary (the null BSDF, scene/media/medium_interface.h).
// Geometric normal (v1-v0) x (v2-v0).
// Explicit triangles/quads must be non-degenerate; degenerate triangles inside mesh
// files are dropped (TriangleMesh::finalize) and reported with a warning.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/limits.h"
#include "scene/loaders/mesh_io.h"
#include "scene/loaders/yaml/yaml_sections.h"
#include "scene/loaders/yaml/yaml_transform.h"

namespace dp::scene::yaml {

namespace {

const std::vector<std::string_view> kCommonKeys = {"type",     "material", "emission", "interior",
                                                   "exterior", "name",     "transform"};

std::vector<Vec3> parse_vertices(const Context& ctx, const YAML::Node& m, size_t count, const std::string& what) {
  const YAML::Node v = require(ctx, m, "vertices", what);
  if (!v.IsSequence() || v.size() != count)
    parse_error(ctx, v, "'vertices' of a " + what + " must be a list of " + std::to_string(count) + " points");
  std::vector<Vec3> out;
  for (size_t i = 0; i < count; ++i) out.push_back(get_vec3(ctx, v[i], "vertices"));
  return out;
}

// Relative tolerance for planarity/degeneracy tests of explicit polygons.
constexpr float kRelTol = 1e-4f;

std::unique_ptr<TriangleMesh> make_triangle(const Context& ctx, const YAML::Node& m) {
  const std::vector<Vec3> v = parse_vertices(ctx, m, 3, "triangle");
  const float scale = std::max({(v[1] - v[0]).norm(), (v[2] - v[0]).norm(), (v[2] - v[1]).norm()});
  if (!((v[1] - v[0]).cross(v[2] - v[0]).norm() > kRelTol * scale * scale))
    value_error(ctx, m["vertices"], "degenerate triangle (zero area)");
  auto mesh = std::make_unique<TriangleMesh>();
  mesh->positions = v;
  mesh->uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  mesh->triangles = {{0, 1, 2}};
  return mesh;
}

std::unique_ptr<TriangleMesh> make_quad(const Context& ctx, const YAML::Node& m) {
  const std::vector<Vec3> v = parse_vertices(ctx, m, 4, "quad");
  const YAML::Node at = m["vertices"];
  float scale = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) scale = std::max(scale, (v[size_t(i)] - v[size_t(j)]).norm());
  const Vec3 n1 = (v[1] - v[0]).cross(v[2] - v[0]);
  const Vec3 n2 = (v[2] - v[0]).cross(v[3] - v[0]);
  const float min_area2 = kRelTol * scale * scale;
  if (!(n1.norm() > min_area2) || !(n2.norm() > min_area2))
    value_error(ctx, at, "degenerate quad (zero area or three collinear vertices)");
  const Vec3 n = n1.normalized();
  const float off_plane = std::abs((v[3] - v[0]).dot(n));
  if (off_plane > kRelTol * scale)
    value_error(ctx, at, "quad is not planar (4th vertex is " + std::to_string(off_plane) + " off the plane of the first three)");
  if (!(n1.dot(n2) > 0.0f)) value_error(ctx, at, "quad vertices are not in order around a convex outline");
  const Vec3 n3 = (v[3] - v[1]).cross(v[0] - v[1]), n4 = (v[2] - v[1]).cross(v[3] - v[1]);
  if (!(n3.dot(n) > 0.0f) && !(n4.dot(n) > 0.0f))
    value_error(ctx, at, "quad vertices are not in order around a convex outline");
  auto mesh = std::make_unique<TriangleMesh>();
  mesh->positions = v;
  mesh->uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

std::unique_ptr<TriangleMesh> make_mesh(const Context& ctx, const YAML::Node& m) {
  const YAML::Node file_node = require(ctx, m, "file", "mesh shape");
  const std::string file = get_string(ctx, file_node, "file");
  std::unique_ptr<TriangleMesh> mesh;
  try {
    mesh = load_mesh(resolve_path(ctx, file));
  } catch (const IoError& e) {
    throw IoError("cannot load mesh '" + quote_input(file) + "': " + e.what(), ctx.file, line_of(file_node));
  } catch (const Error& e) {
    throw ParseError("invalid mesh '" + quote_input(file) + "': " + e.what(), ctx.file, line_of(file_node));
  }
  if (const YAML::Node s = m["smooth"]; s.IsDefined()) mesh->smooth = get_bool(ctx, s, "smooth");
  if (mesh->name.empty()) mesh->name = file;
  return mesh;
}

// Offers a smooth mesh file without normals to the caller's hook (LoadOptions::
// mesh_normals, e.g. CGAL normals for specular/glossy materials). Runs after the
// transform, clean-up and material lookup, before the mesh joins the scene; finalize()
// is re-run because the arrays changed (TriangleMesh contract).
void offer_for_normals(LoadState& st, const YAML::Node& m, TriangleMesh& mesh) {
  if (!st.options || !st.options->mesh_normals || !mesh.smooth || !mesh.normals.empty()) return;
  const Bsdf* material = mesh.material >= 0 ? st.scene.bsdfs().at(size_t(mesh.material)).get() : nullptr;
  if (!st.options->mesh_normals(mesh, material)) return;
  try {
    mesh.finalize();
  } catch (const Error& e) {
    parse_error(st.ctx, m, e.message());
  }
  log::info(st.ctx.file, ":", line_of(m), ": estimated smooth vertex normals for mesh '",
            get_string(st.ctx, m["file"], "file"), "' (", mesh.positions.size(), " vertices)");
}

std::unique_ptr<Shape> make_sphere(const Context& ctx, const YAML::Node& m, const Transform* xf) {
  Vec3 center = get_vec3(ctx, require(ctx, m, "center", "sphere shape"), "center");
  const YAML::Node rn = require(ctx, m, "radius", "sphere shape");
  float radius = get_float(ctx, rn, "radius");
  check_positive(ctx, rn, "radius", radius);
  if (xf) {
    const Vec3 s = xf->scale.cwiseAbs();
    if (std::abs(s.x() - s.y()) > 1e-6f * s.maxCoeff() || std::abs(s.x() - s.z()) > 1e-6f * s.maxCoeff())
      value_error(ctx, m["transform"], "a sphere can only be scaled uniformly (got a non-uniform scale)");
    center = xf->point(center);
    radius *= s.x();
  }
  if (!within_scene_limit(double(center.cwiseAbs().maxCoeff()) + double(radius)))
    value_error(ctx, m, std::string("sphere reaches beyond the scene limit (coordinates at most ") +
                            kMaxSceneMagnitudeText + " in magnitude, after its transform)");
  return std::make_unique<Sphere>(center, radius);
}

void parse_shape(LoadState& st, const YAML::Node& m, size_t index) {
  const Context& ctx = st.ctx;
  const std::string what = "shape " + std::to_string(index);
  expect_map(ctx, m, what);
  const YAML::Node type_node = require(ctx, m, "type", what);
  const std::string type = get_string(ctx, type_node, "type");
  std::vector<std::string_view> allowed = kCommonKeys;
  if (type == "mesh") {
    allowed.insert(allowed.end(), {"file", "smooth"});
  } else if (type == "triangle" || type == "quad") {
    allowed.push_back("vertices");
  } else if (type == "sphere") {
    allowed.insert(allowed.end(), {"center", "radius"});
  } else {
    parse_error(ctx, type_node, "unknown shape type '" + quote_input(type) + "' (mesh, triangle, quad, sphere)");
  }
  check_keys(ctx, m, allowed, type + " shape");

  std::optional<Transform> xf;
  if (const YAML::Node t = m["transform"]; t.IsDefined()) xf = parse_transform(ctx, t);

  std::unique_ptr<Shape> shape;
  TriangleMesh* mesh_file = nullptr;  // a `type: mesh` shape, until it joins the scene
  if (type == "sphere") {
    shape = make_sphere(ctx, m, xf ? &*xf : nullptr);
  } else {
    std::unique_ptr<TriangleMesh> mesh =
        type == "mesh" ? make_mesh(ctx, m) : type == "quad" ? make_quad(ctx, m) : make_triangle(ctx, m);
    if (xf) apply_transform(*xf, *mesh);
    if (type != "mesh") mesh->smooth = false;
    try {
      mesh->finalize();
    } catch (const ValueError& e) {
      value_error(ctx, m, e.message());
    } catch (const Error& e) {
      parse_error(ctx, m, e.message());
    }
    if (mesh->degenerate_skipped > 0)
      log::warn(ctx.file, ":", line_of(m), ": skipped ", mesh->degenerate_skipped,
                " degenerate triangle(s) of mesh '", mesh->name, "'");
    if (mesh->triangles.empty()) value_error(ctx, m, type + " shape has no non-degenerate triangles");
    if (type == "mesh") mesh_file = mesh.get();
    shape = std::move(mesh);
  }

  Rgb emission = Rgb::Zero();
  if (const YAML::Node e = m["emission"]; e.IsDefined()) {
    emission = get_rgb(ctx, e, "emission");
    if (!(shape->area() > 0.0f) || !std::isfinite(shape->area()))
      value_error(ctx, e, "emissive " + type + " has zero area");
  }
  if (const YAML::Node n = m["name"]; n.IsDefined()) shape->name = get_string(ctx, n, "name");
  if (const YAML::Node mat = m["material"]; mat.IsDefined()) {
    if (mat.IsScalar() && mat.Scalar() == "none") {
      // An index-matched medium boundary (SCENE_FORMAT.md): light passes unrefracted.
      if (!m["interior"].IsDefined() && !m["exterior"].IsDefined())
        parse_error(ctx, mat, "'material: none' is allowed only on a shape with 'interior' or 'exterior'");
      if (st.null_material < 0) st.null_material = st.scene.add_bsdf(make_null(), "none");
      shape->material = st.null_material;
    } else {
      shape->material = st.material_index(mat);
    }
  } else if (!(emission > 0.0f).any()) {
    parse_error(ctx, m, "missing required key 'material' in " + type + " shape (only emissive shapes may omit it)");
  }
  if (const YAML::Node i = m["interior"]; i.IsDefined()) shape->interior_medium = st.medium_index(i);
  if (const YAML::Node x = m["exterior"]; x.IsDefined()) shape->exterior_medium = st.medium_index(x);
  if (mesh_file) offer_for_normals(st, m, *mesh_file);
  st.scene.add_shape(std::move(shape), emission);
}

}  // namespace

void parse_shapes(LoadState& st, const YAML::Node& shapes) {
  expect_sequence(st.ctx, shapes, "shapes");
  for (size_t i = 0; i < shapes.size(); ++i) parse_shape(st, shapes[i], i);
}

}  // namespace dp::scene::yaml
