// Mesh normals at load time (issue 6): the YAML loader calls the
// manifold::normal_estimation_hook() passed in scene::LoadOptions for `type: mesh`
// shapes without vertex normals, and only a material with a delta or glossy lobe gets
// them. Scene: a lat-long tessellated unit sphere in an OBJ file without `vn` lines
// (a ball lens when glass) above a diffuse receiver.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "manifold/mesh_normals.h"
#include "scene/loaders/loader.h"
#include "tests/manifold/manifold_fixtures.h"
#include "tests/scene/test_loader_util.h"

using namespace dp;
using namespace dp::test_mf;

namespace {

constexpr int kNu = 32, kNv = 16;  // longitude x latitude segments
constexpr double kEta = 1.5;

// Unit sphere, poles on +-y (the walks below pass near +-z, away from the pole fans),
// seam and poles duplicated as OBJ exporters do, faces wound outward, no vn / vt.
std::string sphere_obj() {
  std::ostringstream o;
  o.precision(9);
  for (int j = 0; j <= kNv; ++j)
    for (int i = 0; i <= kNu; ++i) {
      const double th = kPiD * j / kNv, ph = 2 * kPiD * (i % kNu) / kNu;
      const double sr = (j == 0 || j == kNv) ? 0.0 : std::sin(th);
      const double y = j == 0 ? 1.0 : (j == kNv ? -1.0 : std::cos(th));
      o << "v " << sr * std::cos(ph) << " " << y << " " << sr * std::sin(ph) << "\n";
    }
  auto id = [](int j, int i) { return j * (kNu + 1) + i + 1; };  // 1-based
  for (int j = 0; j < kNv; ++j)
    for (int i = 0; i < kNu; ++i) {
      // a = (j,i), b = (j,i+1), c = (j+1,i): (b - a) x (c - a) points outward.
      if (j > 0) o << "f " << id(j, i) << " " << id(j, i + 1) << " " << id(j + 1, i) << "\n";
      if (j < kNv - 1) o << "f " << id(j, i + 1) << " " << id(j + 1, i + 1) << " " << id(j + 1, i) << "\n";
    }
  return o.str();
}

std::string scene_yaml(const std::string& material) {
  return "version: 1\n"
         "camera: {position: [0, 0, 8], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
         "lights: [{type: point, position: [0, 0, 7], intensity: 1}]\n"
         "materials:\n"
         "  glass: {type: dielectric, ior: 1.5, ext_ior: 1.0}\n"
         "  white: {type: diffuse, albedo: 0.5}\n"
         "shapes:\n"
         "  - {type: mesh, file: sphere.obj, material: " + material + "}\n"
         "  - {type: quad, vertices: [[-9, -9, -6], [9, -9, -6], [9, 9, -6], [-9, 9, -6]], material: white}\n";
}

struct Loaded {
  TempDir dir;
  std::unique_ptr<scene::Scene> scene;
  const scene::TriangleMesh* mesh = nullptr;
};

std::unique_ptr<Loaded> load(const std::string& material, const scene::LoadOptions& options) {
  auto l = std::make_unique<Loaded>();
  l->dir.write("sphere.obj", sphere_obj());
  l->scene = scene::load_scene(l->dir.write("scene.yaml", scene_yaml(material)), options);
  REQUIRE(l->scene->shapes().size() == 2);
  REQUIRE(l->scene->shapes()[0]->kind() == scene::ShapeKind::mesh);
  l->mesh = static_cast<const scene::TriangleMesh*>(l->scene->shapes()[0].get());
  REQUIRE(l->mesh->positions.size() > size_t((kNv - 1) * kNu));  // the OBJ reader drops unused vertices
  return l;
}

// Local frame at barycentrics (b1, b2) of triangle `tri` (near vertex 0 when small).
LocalFrame frame_at(const scene::TriangleMesh& m, size_t tri, double b1, double b2) {
  const auto& t = m.triangles[tri];
  const Vec3d p0 = m.positions[t[0]].cast<double>(), p1 = m.positions[t[1]].cast<double>(),
              p2 = m.positions[t[2]].cast<double>();
  LocalFrame f;
  REQUIRE(local_frame(m, int(tri), (1 - b1 - b2) * p0 + b1 * p1 + b2 * p2, f));
  return f;
}

// A triangle away from the poles (middle latitude band).
size_t equator_triangle(const scene::TriangleMesh& m) { return m.triangles.size() / 2 + 5; }

// Walks the receiver end of the chain x0 -> sphere -> sphere -> receiver (shape 0 is
// the sphere, refracting) in kSweepSteps steps along a line, each walk starting from
// the previous converged chain.
constexpr int kSweepSteps = 40;
struct Sweep {
  int converged = 0, crossed = 0;  // walks that converged; entry-triangle changes
  double max_move = 0;             // largest entry-point move between converged steps
};
Sweep sweep(const scene::Scene& s) {
  const std::map<int, Material> specular{{0, Material{Interaction::refraction, kEta}}};
  const Vec3d x0(0.35, 0.1, 6.0);
  const auto c = trace_chain(s, specular, make_point(x0), Vec3d(0.3, 0.12, 0.9) - x0, 2);
  REQUIRE(c);
  const Vec3d start = c->v.back().p();
  WalkSettings ws;
  ws.check_reversible = true;
  Chain cur = *c;
  Sweep out;
  for (int k = 1; k <= kSweepSteps; ++k) {
    const WalkResult r = walk(s, cur, start + Vec3d(0.02 * k, 0.005 * k, 0), ws);
    if (!r.ok()) continue;
    ++out.converged;
    CHECK(constraint_residual(r.chain) < 1e-7);
    out.max_move = std::max(out.max_move, (r.chain.v[1].p() - cur.v[1].p()).norm());
    if (r.chain.v[1].prim != cur.v[1].prim) ++out.crossed;
    cur = r.chain;
  }
  return out;
}

}  // namespace

TEST_CASE("loader + normal hook: a glass OBJ sphere without vn gets smooth normals and dn/du", "[unit]") {
  const auto l = load("glass", {manifold::normal_estimation_hook()});
  const scene::TriangleMesh& m = *l->mesh;
  REQUIRE(m.normals.size() == m.positions.size());
  CHECK(m.smooth);
  const double h = kPiD / kNv;
  for (size_t k = 0; k < m.positions.size(); ++k) {
    const Vec3d radial = m.positions[k].cast<double>().normalized();
    CHECK(radial.dot(m.normals[k].cast<double>()) > std::cos(h * h));  // outward, O(h^2)
  }

  // Near a vertex the interpolated shading normal follows the sphere (error O(h^2))
  // while the face normal is off by O(h); the normal has curvature ~1 / R = 1.
  const size_t tri = equator_triangle(m);
  const LocalFrame f = frame_at(m, tri, 0.05, 0.05);
  const Vec3d radial = f.p.normalized();
  const double shading_err = std::acos(std::min(1.0, f.n.dot(radial)));
  const double flat_err = std::acos(std::min(1.0, f.ng.dot(radial)));
  INFO("shading normal " << shading_err << " rad, face normal " << flat_err << " rad from the radial direction");
  CHECK(flat_err > 0.2 * h);
  CHECK(shading_err < 0.25 * flat_err);
  CHECK(f.dn1.norm() > 0.5);
  CHECK(f.dn2.norm() > 0.5);
  const double curv = 0.5 * (f.dn1.dot(f.T1) + f.dn2.dot(f.T2));
  CHECK(std::abs(curv - 1.0) < 0.1);

  // The float surface point of a ray hit (what the tracers see) carries it too.
  const auto hit = l->scene->intersect(Ray{Vec3(0.13f, 0.07f, 5.0f), Vec3(0, 0, -1), 0.0f, kInfinity});
  REQUIRE(hit);
  REQUIRE(hit->shape == 0);
  CHECK((hit->dndu.norm() > 0.0f || hit->dndv.norm() > 0.0f));
  CHECK(hit->shading.n.dot(hit->ng) < 1.0f - 1e-6f);

  // Ball lens: the end of x0 -> glass -> glass -> receiver walks along a line on the
  // receiver; every walk converges and the entry point moves continuously across
  // triangle edges (the refracted direction turns continuously).
  const Sweep sw = sweep(*l->scene);
  INFO("converged " << sw.converged << " of " << kSweepSteps << ", entry triangles crossed " << sw.crossed
                    << ", largest entry-point move " << sw.max_move);
  CHECK(sw.converged == kSweepSteps);
  CHECK(sw.crossed >= 2);  // the sweep really crosses triangle edges
  CHECK(sw.max_move < 0.02);
}

TEST_CASE("loader + normal hook: a diffuse OBJ sphere without vn stays flat shaded", "[unit]") {
  const auto l = load("white", {manifold::normal_estimation_hook()});
  CHECK(l->mesh->normals.empty());
  const LocalFrame f = frame_at(*l->mesh, equator_triangle(*l->mesh), 0.05, 0.05);
  CHECK(f.dn1.norm() == 0.0);
  CHECK(f.dn2.norm() == 0.0);
  CHECK((f.n - f.ng).norm() < 1e-12);
}

TEST_CASE("loader without a normal hook: a glass OBJ sphere without vn stays flat shaded", "[unit]") {
  const auto l = load("glass", {});
  CHECK(l->mesh->normals.empty());
  const LocalFrame f = frame_at(*l->mesh, equator_triangle(*l->mesh), 0.05, 0.05);
  CHECK(f.dn1.norm() == 0.0);
  CHECK(f.dn2.norm() == 0.0);
  CHECK((f.n - f.ng).norm() < 1e-12);
  // The contrast that makes the smooth sweep above meaningful: through flat facets the
  // end point jumps at triangle edges, so targets in the gaps are unreachable.
  const Sweep sw = sweep(*l->scene);
  INFO("converged " << sw.converged << " of " << kSweepSteps);
  CHECK(sw.converged < kSweepSteps / 2);
}

TEST_CASE("loader calls the normal hook only for smooth mesh files without normals", "[unit]") {
  TempDir dir;
  dir.write("sphere.obj", sphere_obj());
  dir.write("tri_vn.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  const std::string yaml =
      "version: 1\n"
      "camera: {position: [0, 0, 8], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
      "lights: [{type: point, position: [0, 0, 7], intensity: 1}]\n"
      "materials: {glass: {type: dielectric, ior: 1.5}}\n"
      "shapes:\n"
      "  - {type: mesh, file: sphere.obj, material: glass, name: called}\n"
      "  - {type: mesh, file: sphere.obj, material: glass, smooth: false}\n"
      "  - {type: mesh, file: tri_vn.obj, material: glass}\n"
      "  - {type: quad, vertices: [[-9, -9, -6], [9, -9, -6], [9, 9, -6], [-9, 9, -6]], material: glass}\n"
      "  - {type: triangle, vertices: [[0, 0, -4], [1, 0, -4], [0, 1, -4]], emission: 1}\n";
  int calls = 0;
  scene::LoadOptions opt;
  opt.mesh_normals = [&](scene::TriangleMesh& mesh, const scene::Bsdf* material) {
    ++calls;
    CHECK(mesh.normals.empty());
    CHECK(mesh.smooth);
    CHECK(material != nullptr);
    CHECK(mesh.positions.size() > size_t((kNv - 1) * kNu));
    return false;  // declined: the mesh must stay as it was
  };
  const auto s = scene::load_scene(dir.write("scene.yaml", yaml), opt);
  CHECK(calls == 1);
  CHECK(static_cast<const scene::TriangleMesh&>(*s->shapes()[0]).normals.empty());
}
