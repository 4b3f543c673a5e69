// Mitsuba shapes, baked into world space.
//   obj, ply, serialized (shape_index): filename, face_normals, flip_normals,
//       flip_tex_coords (obj, default true). Meshes without vertex normals get
//       angle-weighted smooth normals unless face_normals (as Mitsuba recomputes them).
//   rectangle [-1,1]^2 at z = 0, normal +z;  cube [-1,1]^3, outward normals;
//   disk: unit disk at z = 0, normal +z, tessellated into kSegments triangles;
//   cylinder: p0 (0,0,0), p1 (0,0,1), radius (1), open tube, outward normals,
//       kSegments quads with smooth normals;
//   sphere: center, radius; to_world must be a similarity (uniform scale).
//   instance: a <ref> to a shapegroup + to_world; the group's shapes are baked per
//       instance.
// Tessellation: with kSegments = 256 the disk's and cylinder's area is low by
// (2 pi / 256)^2 / 6 = 1e-4 relative; shading normals of the cylinder are exact.
// Geometric normals (the emitting side of an area light): analytic shapes keep
// Mitsuba's transformed normal (inverse transpose), so a mirroring to_world reverses
// their winding; meshes keep the cross product of their transformed edges as Mitsuba
// does. flip_normals reverses both.
// Common: one nested/referenced bsdf (none: Mitsuba's defaults — diffuse 0.5, null on
// a medium boundary, black on an emitter), an area emitter (radiance), interior and
// exterior media. UVs are stored as (u, 1 - v) of Mitsuba's (see mitsuba_textures.cpp).
#include <cmath>

#include "core/error.h"
#include "core/log.h"
#include "scene/limits.h"
#include "scene/loaders/mesh_io.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"
#include "scene/loaders/mitsuba/mitsuba_serialized.h"

namespace dp::scene::mitsuba {

namespace {

constexpr int kSegments = 256;

void add_vertex(TriangleMesh& m, const Vec3& p, const Vec2& uv_mts, const Vec3* n = nullptr) {
  m.positions.push_back(p);
  m.uvs.emplace_back(uv_mts.x(), 1.0f - uv_mts.y());
  if (n) m.normals.push_back(*n);
}

std::unique_ptr<TriangleMesh> rectangle() {
  auto m = std::make_unique<TriangleMesh>();
  add_vertex(*m, Vec3(-1, -1, 0), Vec2(0, 0));
  add_vertex(*m, Vec3(1, -1, 0), Vec2(1, 0));
  add_vertex(*m, Vec3(1, 1, 0), Vec2(1, 1));
  add_vertex(*m, Vec3(-1, 1, 0), Vec2(0, 1));
  m->triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

std::unique_ptr<TriangleMesh> cube() {
  auto m = std::make_unique<TriangleMesh>();
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      Vec3 n = Vec3::Zero();
      n[axis] = sign;
      // Tangents s, t with s x t = n.
      Vec3 s = Vec3::Zero();
      s[(axis + 1) % 3] = 1;
      Vec3 t = n.cross(s);
      const uint32_t base = uint32_t(m->positions.size());
      add_vertex(*m, n - s - t, Vec2(0, 0));
      add_vertex(*m, n + s - t, Vec2(1, 0));
      add_vertex(*m, n + s + t, Vec2(1, 1));
      add_vertex(*m, n - s + t, Vec2(0, 1));
      m->triangles.push_back({base, base + 1, base + 2});
      m->triangles.push_back({base, base + 2, base + 3});
    }
  return m;
}

std::unique_ptr<TriangleMesh> disk() {
  auto m = std::make_unique<TriangleMesh>();
  for (int i = 0; i < kSegments; ++i) {
    const float a0 = 2.0f * kPi * float(i) / kSegments, a1 = 2.0f * kPi * float(i + 1) / kSegments;
    const uint32_t base = uint32_t(m->positions.size());
    // Mitsuba's disk uv = (r, phi / 2 pi).
    add_vertex(*m, Vec3(0, 0, 0), Vec2(0, (float(i) + 0.5f) / kSegments));
    add_vertex(*m, Vec3(std::cos(a0), std::sin(a0), 0), Vec2(1, float(i) / kSegments));
    add_vertex(*m, Vec3(std::cos(a1), std::sin(a1), 0), Vec2(1, float(i + 1) / kSegments));
    m->triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

// Unit tube along z in [0, 1], outward normals; uv = (phi / 2 pi, z).
std::unique_ptr<TriangleMesh> tube() {
  auto m = std::make_unique<TriangleMesh>();
  for (int i = 0; i <= kSegments; ++i) {
    const float a = 2.0f * kPi * float(i) / kSegments, u = float(i) / kSegments;
    const Vec3 n(std::cos(a), std::sin(a), 0);
    add_vertex(*m, n, Vec2(u, 0), &n);
    add_vertex(*m, n + Vec3(0, 0, 1), Vec2(u, 1), &n);
  }
  for (uint32_t i = 0; i < uint32_t(kSegments); ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    m->triangles.push_back({a, c, d});
    m->triangles.push_back({a, d, b});
  }
  return m;
}

// Angle-weighted vertex normals from the faces (Thürmer and Wüthrich 1998).
void smooth_normals(TriangleMesh& m) {
  m.normals.assign(m.positions.size(), Vec3::Zero());
  for (const auto& tri : m.triangles) {
    const Vec3 p[3] = {m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]};
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n.squaredNorm() > 0.0f) || !n.allFinite()) continue;
    const Vec3 nn = n.normalized();
    for (int k = 0; k < 3; ++k) {
      const Vec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      const float angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      m.normals[tri[size_t(k)]] += angle * nn;
    }
  }
  for (Vec3& n : m.normals) {
    const float len = n.norm();
    n = len > 0.0f && std::isfinite(len) ? Vec3(n / len) : Vec3(0, 0, 1);
  }
}

std::unique_ptr<TriangleMesh> load_file_mesh(Loader& ld, Object& o, bool& face_normals, bool& flip_v) {
  const XmlElement* fn = o.take("filename");
  if (!fn || fn->tag != "string") o.error(o.describe() + " needs a <string name=\"filename\">");
  const std::string file = o.value_of(*fn);
  const std::string path = ld.resolve_path(*fn, file);
  std::unique_ptr<TriangleMesh> mesh;
  try {
    if (o.type() == "serialized") {
      SerializedMesh s = load_serialized(path, o.get_int("shape_index", 0));
      face_normals = face_normals || s.face_normals;
      mesh = std::move(s.mesh);
    } else {
      mesh = o.type() == "obj" ? load_obj(path) : load_ply(path);
    }
  } catch (const IoError& e) {
    throw IoError("cannot load mesh '" + quote_input(file) + "': " + e.what(), fn->file_name(), fn->line);
  } catch (const Error& e) {
    throw ParseError("invalid mesh '" + quote_input(file) + "': " + e.what(), fn->file_name(), fn->line);
  }
  // Mitsuba flips OBJ texture coordinates by default (then v = 0 is an image's top
  // row); in deltapath's convention that is the file's own v.
  flip_v = o.type() == "obj" ? !o.get_bool("flip_tex_coords", true) : true;
  if (mesh->name.empty()) mesh->name = file;
  return mesh;
}

std::unique_ptr<Sphere> sphere(Object& o, const Mat4d& m) {
  const Vec3 c = o.get_point("center", Vec3::Zero());
  const float r = o.get_float("radius", 1.0f);
  if (!(r > 0.0f)) o.value_error_at(o.elem(), "sphere 'radius' must be > 0");
  const Eigen::Matrix3d a = m.block<3, 3>(0, 0);
  const double s2 = (a.transpose() * a).trace() / 3.0;
  if (!((a.transpose() * a - s2 * Eigen::Matrix3d::Identity()).norm() <= 1e-5 * s2) || !(s2 > 0.0))
    o.error("a sphere's to_world must be a rotation, uniform scale and translation");
  const Vec3d center = a * c.cast<double>() + m.block<3, 1>(0, 3);
  const double radius = std::sqrt(s2) * double(r);
  if (!(center.cwiseAbs().maxCoeff() + radius <= kMaxSceneMagnitude))
    o.value_error_at(o.elem(), std::string("sphere reaches beyond the scene limit (coordinates at most ") +
                                   kMaxSceneMagnitudeText + " in magnitude, after its to_world)");
  return std::make_unique<Sphere>(center.cast<float>(), float(radius));
}

void transform_mesh(TriangleMesh& mesh, const Mat4d& m, bool swap_winding) {
  const Eigen::Matrix3d a = m.block<3, 3>(0, 0);
  const Eigen::Matrix3d nt = a.inverse().transpose();
  for (Vec3& p : mesh.positions) p = (a * p.cast<double>() + m.block<3, 1>(0, 3)).cast<float>();
  for (Vec3& n : mesh.normals) n = (nt * n.cast<double>()).normalized().cast<float>();
  if (swap_winding)
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
}

}  // namespace

void build_shape(Loader& ld, const XmlElement& e, const Mat4d& parent) {
  Object o(ld, e);
  const std::string& t = o.type();
  if (t == "instance") {
    const std::vector<const XmlElement*> groups = o.objects("shape");
    if (groups.size() != 1 || !groups[0]->attribute("type") || *groups[0]->attribute("type") != "shapegroup")
      o.error("an instance needs exactly one reference to a shapegroup");
    const Mat4d m = parent * o.get_transform("to_world");
    o.finish();
    for (const XmlElement& c : groups[0]->children) {
      if (c.tag != "shape") throw ParseError("a shapegroup may only contain shapes", c.file_name(), c.line);
      build_shape(ld, c, m);
    }
    return;
  }
  const Mat4d m = parent * o.get_transform("to_world");
  if (!m.allFinite() || m.block<3, 3>(0, 0).determinant() == 0.0) o.error("to_world is singular");
  const bool mirror = m.block<3, 3>(0, 0).determinant() < 0.0;
  const bool flip = o.get_bool("flip_normals", false);
  std::unique_ptr<Shape> shape;
  if (t == "sphere") {
    auto s = sphere(o, m);
    s->flip_normals = flip;
    shape = std::move(s);
  } else {
    std::unique_ptr<TriangleMesh> mesh;
    bool face_normals = false, analytic = true, flip_v = false;
    if (t == "rectangle") mesh = rectangle();
    else if (t == "cube") mesh = cube(), analytic = false;
    else if (t == "disk") mesh = disk();
    else if (t == "cylinder") {
      const Vec3d p0 = o.get_point("p0", Vec3::Zero()).cast<double>(), p1 = o.get_point("p1", Vec3(0, 0, 1)).cast<double>();
      const double r = double(o.get_float("radius", 1.0f));
      if (!(r > 0.0) || !((p1 - p0).norm() > 0.0)) o.value_error_at(e, "cylinder needs radius > 0 and p0 != p1");
      const Vec3d d = (p1 - p0).normalized();
      const Frame f = Frame::from_normal(d.cast<float>());
      Mat4d local = Mat4d::Identity();
      local.block<3, 1>(0, 0) = f.s.cast<double>() * r;
      local.block<3, 1>(0, 1) = f.t.cast<double>() * r;
      local.block<3, 1>(0, 2) = d * (p1 - p0).norm();
      local.block<3, 1>(0, 3) = p0;
      mesh = tube();
      transform_mesh(*mesh, local, false);
    } else if (t == "obj" || t == "ply" || t == "serialized") {
      face_normals = o.get_bool("face_normals", false);
      mesh = load_file_mesh(ld, o, face_normals, flip_v);
      analytic = false;
      if (flip_v)
        for (Vec2& uv : mesh->uvs) uv.y() = 1.0f - uv.y();
      o.ignore("max_smooth_angle", "vertex normals are used as given");
    } else if (t == "shapegroup") {
      o.error("a shapegroup can only appear at scene level");
    } else {
      o.error("unsupported shape type '" + quote_input(t) + "' (obj, ply, serialized, rectangle, cube, disk, cylinder, sphere, instance)");
    }
    if (face_normals) {
      mesh->normals.clear();
      mesh->smooth = false;
    } else if (mesh->normals.empty() && !(t == "rectangle" || t == "disk" || t == "cube")) {
      smooth_normals(*mesh);
    }
    if (t == "rectangle" || t == "disk" || t == "cube") mesh->smooth = false;
    transform_mesh(*mesh, m, analytic && mirror);
    if (flip) {
      for (auto& tri : mesh->triangles) std::swap(tri[1], tri[2]);
      for (Vec3& n : mesh->normals) n = -n;
    }
    try {
      mesh->finalize();
    } catch (const ValueError& err) {
      o.value_error_at(e, err.message());
    } catch (const Error& err) {
      o.error(err.message());
    }
    if (mesh->degenerate_skipped > 0)
      ld.warn(e, "skipped " + std::to_string(mesh->degenerate_skipped) + " degenerate triangle(s) of '" + quote_input(mesh->name) + "'");
    if (mesh->triangles.empty()) o.value_error_at(e, t + " shape has no non-degenerate triangles");
    shape = std::move(mesh);
  }
  if (const std::string* id = e.attribute("id")) shape->name = *id;

  Rgb emission = Rgb::Zero();
  const std::vector<const XmlElement*> emitters = o.objects("emitter");
  if (emitters.size() > 1) o.error("a shape can carry at most one emitter");
  if (!emitters.empty()) {
    Object eo(ld, *emitters[0]);
    if (eo.type() != "area") eo.error("only 'area' emitters can be attached to a shape (got '" + quote_input(eo.type()) + "')");
    const XmlElement* rad = eo.take("radiance");
    if (!rad) eo.error("area emitter needs a 'radiance'");
    if (rad->tag == "texture" || rad->tag == "ref") eo.error_at(*rad, "textured area emitters are not supported");
    emission = parse_color(ld, *rad);
    if (!(emission >= 0.0f).all()) eo.value_error_at(*rad, "'radiance' must be >= 0");
    eo.ignore("sampling_weight", "light selection only (deltapath selects emitters uniformly)");
    eo.finish();
    if (!(shape->area() > 0.0f)) o.value_error_at(e, "emissive shape has zero area");
  }
  const XmlElement* interior = o.named_object("interior");
  const XmlElement* exterior = o.named_object("exterior");
  if (interior) shape->interior_medium = ld.medium_index(*interior);
  if (exterior) shape->exterior_medium = ld.medium_index(*exterior);
  const std::vector<const XmlElement*> bsdfs = o.objects("bsdf");
  if (bsdfs.size() > 1) o.error("a shape can have at most one bsdf");
  if (!bsdfs.empty()) shape->material = ld.bsdf_index(*bsdfs[0]);
  else if (!emitters.empty()) shape->material = -1;  // black: emits, reflects nothing
  else shape->material = ld.builtin_bsdf(interior || exterior ? "null" : "diffuse");
  o.finish();
  ld.scene().add_shape(std::move(shape), emission);
}

}  // namespace dp::scene::mitsuba
