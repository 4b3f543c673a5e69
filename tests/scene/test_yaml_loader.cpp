// YAML scene loader: every error class of SCENE_FORMAT.md / issue 2 ("Bad input")
// produces its typed error with "file:line:" and a key phrase; valid scenes (including
// every built-in scenes/*.yaml) load with the right contents.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/loaders/loader.h"
#include "test_loader_util.h"

using namespace dp;
using namespace dp::scene;
using Catch::Matchers::Contains;

namespace {

const std::string kPath = "mem/test.yaml";

// Lines 1-3 of most test documents; test-specific text starts at line 4.
const std::string kHead =
    "version: 1\n"
    "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
    "lights: [{type: point, position: [0, 0, 4], intensity: 1}]\n";
// Lines 4-5: a material named white.
const std::string kWhite =
    "materials:\n"
    "  white: {type: diffuse, albedo: 0.5}\n";

template <typename E>
void require_error(const std::string& yaml, int line, const std::string& phrase, const std::string& path = kPath) {
  require_load_error<E>([](const std::string& t, const std::string& p) { return load_scene_yaml_string(t, p); }, yaml, line, phrase,
                        path);
}

std::unique_ptr<Scene> load(const std::string& yaml, const std::string& path = kPath) {
  return load_scene_yaml_string(yaml, path);
}

const TriangleMesh& mesh_at(const Scene& s, size_t i) {
  REQUIRE(s.shapes().size() > i);
  REQUIRE(s.shapes()[i]->kind() == ShapeKind::mesh);
  return static_cast<const TriangleMesh&>(*s.shapes()[i]);
}

}  // namespace

TEST_CASE("yaml: malformed YAML is a ParseError with its line", "[unit]") {
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0]\n", 7, "malformed YAML");
  require_error<ParseError>(kHead + "materials:\n  white: {type: diffuse\n    albedo: 0.5\n", 6, "malformed YAML");
  require_error<ParseError>("- just\n- a list\n", 1, "must be a YAML map");
}

TEST_CASE("yaml: unknown keys are errors anywhere", "[unit]") {
  require_error<ParseError>(kHead + "colour: 1\n", 4, "unknown key 'colour'");
  require_error<ParseError>(kHead + "materials:\n  white: {type: diffuse, albedo: 0.5, roughnes: 0.1}\n", 5,
                            "unknown key 'roughnes' in material 'white'");
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1,\n"
                                             "     material: white, smooth: true}\n",
                            8, "unknown key 'smooth' in sphere shape");
  require_error<ParseError>(
      "version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8], zoom: 2}\n", 2,
      "unknown key 'zoom' in camera");
  require_error<ParseError>(kHead + kWhite +
                                "shapes:\n  - {type: quad, material: white, vertices: [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n"
                                "     transform: {translate: [0, 0, 1], shear: 1}}\n",
                            8, "unknown key 'shear' in transform");
  require_error<ParseError>(
      kHead + "materials:\n  t: {type: diffuse, albedo: {checkerboard: {color0: 0, color1: 1, size: 4}}}\n", 5,
      "unknown key 'size'");
  require_error<ParseError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
                            "lights:\n  - {type: point, position: [0, 0, 4], intensity: 1, radius: 2}\n",
                            4, "unknown key 'radius' in point light");
  require_error<ParseError>(kHead + "media:\n  fog: {type: homogeneous, sigma_a: 0, sigma_s: 1, phase: {type: isotropic, g: 0.5}}\n",
                            5, "unknown key 'g' in isotropic phase function");
  require_error<ParseError>(kHead + "colour: 1\ncolour: 2\n", 4, "unknown key 'colour'");
  require_error<ParseError>(kHead + kWhite + "lights: []\n", 6, "duplicate key 'lights'");
}

TEST_CASE("yaml: wrong types are ParseErrors", "[unit]") {
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: big, material: white}\n",
                            7, "'radius': expected a number, got 'big'");
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0], radius: 1, material: white}\n",
                            7, "'center': expected a list of 3 numbers");
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: '1', material: white}\n",
                            7, "'radius': expected a number");
  require_error<ParseError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40,\n"
                            "         resolution: [8.5, 8]}\n",
                            3, "'resolution': expected an integer");
  require_error<ParseError>(kHead + kWhite + "shapes: {type: sphere}\n", 6, "shapes: expected a list");
  require_error<ParseError>(kHead + "materials:\n  white: {type: diffuse, albedo: [1, 0]}\n", 5,
                            "'albedo': expected an RGB list");
  require_error<ParseError>(kHead + "materials:\n  white: {type: velvet}\n", 5, "unknown material type 'velvet'");
}

TEST_CASE("yaml: missing required keys are ParseErrors at the enclosing map", "[unit]") {
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], material: white}\n", 7,
                            "missing required key 'radius' in sphere shape");
  require_error<ParseError>("camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n", 1,
                            "missing required key 'version'");
  require_error<ParseError>("version: 1\nlights: []\n", 1, "missing required key 'camera'");
  require_error<ParseError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40}\n", 2,
                            "missing required key 'resolution' in camera");
  require_error<ParseError>(kHead + "materials:\n  white: {type: dielectric, roughness: 0.1}\n", 5,
                            "missing required key 'ior'");
  require_error<ParseError>(kHead + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n", 5,
                            "missing required key 'material'");
  require_error<ParseError>("version: 2\n", 1, "unsupported scene format version 2");
}

TEST_CASE("yaml: non-finite numbers are ValueErrors", "[unit]") {
  require_error<ValueError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: .inf, material: white}\n",
                            7, "not a finite number");
  require_error<ValueError>(kHead + "materials:\n  white: {type: diffuse, albedo: [.nan, 0.5, 0.5]}\n", 5,
                            "not a finite number");
  require_error<ValueError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 1e999, 0], radius: 1, material: white}\n",
                            7, "not a finite number");
}

TEST_CASE("yaml: out-of-range values are ValueErrors", "[unit]") {
  const std::string sphere = "shapes:\n  - {type: sphere, center: [0, 0, 0], material: white,\n";
  require_error<ValueError>(kHead + kWhite + sphere + "     radius: -1}\n", 8, "'radius' must be > 0");
  require_error<ValueError>(kHead + kWhite + sphere + "     radius: 0}\n", 8, "'radius' must be > 0");
  require_error<ValueError>(kHead + "materials:\n  glass: {type: dielectric, ior: 0}\n", 5, "'ior' must be > 0");
  require_error<ValueError>(kHead + "materials:\n  glass: {type: dielectric, ior: 1.5, ext_ior: -1}\n", 5,
                            "'ext_ior' must be > 0");
  require_error<ValueError>(kHead + "materials:\n  p: {type: plastic, diffuse: 0.5, ior: -1.5}\n", 5, "'ior' must be > 0");
  require_error<ValueError>(kHead + "materials:\n  m: {type: conductor, reflectance: 0.9, roughness: -0.1}\n", 5,
                            "'roughness' must be >= 0");
  require_error<ValueError>(kHead + "materials:\n  m: {type: dielectric, ior: 1.5, roughness: -0.01}\n", 5,
                            "'roughness' must be >= 0");
  require_error<ValueError>(kHead + "materials:\n  g: {type: phong, diffuse: 0.2, specular: 0.5, exponent: -2}\n", 5,
                            "'exponent' must be >= 0");
  require_error<ValueError>(kHead + "materials:\n  g: {type: phong, diffuse: 0.6, specular: 0.6, exponent: 10}\n", 5,
                            "diffuse + specular must be <= 1");
  require_error<ValueError>(kHead + "materials:\n  w: {type: diffuse, albedo: [1.2, 0.5, 0.5]}\n", 5, "must be <= 1");
  require_error<ValueError>(kHead + "materials:\n  w: {type: diffuse, albedo: -0.5}\n", 5, "must be >= 0");
  require_error<ValueError>(kHead + "materials:\n  m: {type: conductor, reflectance: 0.9, distribution: phong}\n", 5,
                            "'distribution' must be beckmann or ggx");
  require_error<ValueError>(kHead + "media:\n  fog: {type: homogeneous, sigma_a: 0, sigma_s: 1,\n"
                                    "        phase: {type: hg, g: 1}}\n",
                            6, "-1 < g < 1");
  require_error<ValueError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 180, resolution: [8, 8]}\n",
                            2, "'fov' must be in (0, 180)");
  require_error<ValueError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [0, 8]}\n",
                            2, "'resolution' must be between");
  require_error<ValueError>(kHead + kWhite +
                                "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: white,\n"
                                "     transform: {scale: [1, 2, 1]}}\n",
                            8, "scaled uniformly");
  require_error<ValueError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
                            "lights:\n  - {type: spot, position: [0, 0, 4], direction: [0, 0, -1], intensity: 1,\n"
                            "     cutoff: 20, falloff_start: 30}\n",
                            5, "'falloff_start' must be in [0, cutoff]");
  require_error<ValueError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
                            "lights:\n  - {type: directional, direction: [0, 0, 0], irradiance: 1}\n",
                            4, "direction must be non-zero");
}

TEST_CASE("yaml: zero-area and degenerate emitters are ValueErrors", "[unit]") {
  require_error<ValueError>(kHead + "shapes:\n  - {type: quad, emission: [1, 1, 1],\n"
                                    "     vertices: [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]}\n",
                            6, "degenerate quad");
  require_error<ValueError>(kHead + "shapes:\n  - {type: triangle, emission: 1, vertices: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]}\n",
                            5, "degenerate triangle");
  require_error<ValueError>(kHead + "shapes:\n  - {type: triangle, emission: 1, vertices: [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}\n",
                            5, "degenerate triangle");
  // A mesh whose only triangle is degenerate: nothing is left to emit from.
  TempDir dir;
  dir.write("flat.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n");
  require_error<ValueError>(kHead + "shapes:\n  - {type: mesh, file: flat.ply, emission: 1}\n", 5,
                            "no non-degenerate triangles", dir.path("scene.yaml"));
}

TEST_CASE("yaml: non-planar and out-of-order quads are ValueErrors", "[unit]") {
  require_error<ValueError>(kHead + kWhite + "shapes:\n  - {type: quad, material: white,\n"
                                             "     vertices: [[0, 0, 0], [1, 0, 0], [1, 1, 0.2], [0, 1, 0]]}\n",
                            8, "not planar");
  require_error<ValueError>(kHead + kWhite + "shapes:\n  - {type: quad, material: white,\n"
                                             "     vertices: [[0, 0, 0], [1, 1, 0], [1, 0, 0], [0, 1, 0]]}\n",
                            8, "not in order");
}

TEST_CASE("yaml: references to undefined materials and media are ParseErrors", "[unit]") {
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1,\n"
                                             "     material: whit}\n",
                            8, "undefined material 'whit'");
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: white,\n"
                                             "     interior: smoke}\n",
                            8, "undefined medium 'smoke'");
  require_error<ParseError>(kHead + "medium: fog\n", 4, "undefined medium 'fog'");
}

TEST_CASE("yaml: missing and unreadable files are IoErrors at the referencing line", "[unit]") {
  TempDir dir;
  const std::string path = dir.path("scene.yaml");
  require_error<IoError>(kHead + kWhite + "shapes:\n  - {type: mesh, material: white,\n     file: nothere.obj}\n", 8,
                         "cannot load mesh 'nothere.obj'", path);
  require_error<IoError>(kHead + kWhite + "shapes:\n  - {type: mesh, material: white, file: nothere.ply}\n", 7,
                         "cannot load mesh 'nothere.ply'", path);
  require_error<IoError>(kHead + kWhite + "shapes:\n  - {type: mesh, material: white, file: mesh.stl}\n", 7,
                         "unsupported mesh format", path);
  require_error<IoError>(kHead + "materials:\n  t: {type: diffuse, albedo: {texture: tex/none.png}}\n", 5,
                         "cannot read texture 'tex/none.png'", path);
  require_error<IoError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
                         "lights:\n  - {type: environment, file: sky.exr}\n",
                         4, "cannot read environment map 'sky.exr'", path);
  // A file that exists but is not a mesh.
  dir.write("broken.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\n2\n");
  require_error<ParseError>(kHead + kWhite + "shapes:\n  - {type: mesh, material: white, file: broken.ply}\n", 7,
                            "invalid mesh 'broken.ply'", path);
  // Scene files themselves.
  CHECK_THROWS_AS(load_scene(dir.path("missing.yaml")), IoError);
  // .xml goes to the Mitsuba importer, which names the file it cannot open.
  CHECK_THROWS_WITH(load_scene(dir.path("scene.xml")), Contains("scene.xml") && Contains("cannot open XML file"));
}

TEST_CASE("yaml: camera and integrator blocks", "[unit]") {
  auto s = load("version: 1\n"
                "camera: {type: perspective, position: [1, 2, 3], direction: [0, 0, -2], up: [0, 1, 0],\n"
                "         fov: 30, fov_axis: x, resolution: [64, 32]}\n"
                "integrator: {type: gpt, max_depth: 5, spp: 16, alpha: 0.2, reconstruction: L1,\n"
                "             buffers: [a, b]}\n"
                "lights: [{type: directional, direction: [0, -1, 0], irradiance: [1, 2, 3]}]\n");
  const CameraDesc& c = s->camera().desc();
  CHECK(c.position == Vec3(1, 2, 3));
  CHECK(c.look_at.isApprox(Vec3(1, 2, 2)));
  CHECK(c.fov_deg == 30.0f);
  CHECK(c.fov_axis_x);
  CHECK(c.width == 64);
  CHECK(c.height == 32);
  const IntegratorDefaults& d = s->integrator_defaults();
  CHECK(d.type == "gpt");
  CHECK(d.max_depth == 5);
  CHECK(d.spp == 16);
  REQUIRE(d.settings.size() == 3);
  CHECK(d.settings.at("alpha") == "0.2");
  CHECK(d.settings.at("reconstruction") == "L1");
  CHECK(d.settings.at("buffers") == "[a, b]");
  CHECK(s->caps().has_delta_lights);
  require_error<ParseError>("version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], direction: [0, 0, -1],\n"
                            "         fov: 40, resolution: [8, 8]}\n",
                            2, "either 'look_at' or 'direction'");
  require_error<ValueError>(kHead + "integrator: {max_depth: 0}\n", 4, "'max_depth' must be >= 1");
}

TEST_CASE("yaml: materials are added on first use, media and lights are wired", "[unit]") {
  auto s = load(kHead +
                "materials:\n"
                "  white: {type: diffuse, albedo: [0.5, 0.5, 0.5]}\n"
                "  unused: {type: dielectric, ior: 1.5}\n"
                "  metal: {type: conductor, eta: [0.2, 0.9, 1.1], k: [3.9, 2.4, 2.1], roughness: 0.1,\n"
                "          distribution: beckmann}\n"
                "media:\n"
                "  fog: {type: homogeneous, sigma_a: 0.1, sigma_s: [0.2, 0.3, 0.4], phase: {type: hg, g: 0.3}}\n"
                "shapes:\n"
                "  - {type: sphere, center: [0, 0, 0], radius: 1, material: metal, interior: fog}\n"
                "  - {type: quad, material: white, emission: [2, 2, 2],\n"
                "     vertices: [[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]]}\n"
                "medium: fog\n");
  REQUIRE(s->bsdf_names().size() == 2);
  CHECK(s->bsdf_names()[0] == "metal");
  CHECK(s->bsdf_names()[1] == "white");
  CHECK_FALSE(s->caps().has_specular);  // the unused dielectric is not in the scene
  REQUIRE(s->media().size() == 1);
  CHECK(s->media()[0].sigma_s.isApprox(Rgb(0.2f, 0.3f, 0.4f)));
  CHECK(s->media()[0].phase.type == PhaseFunctionDesc::Type::hg);
  CHECK(s->media()[0].phase.g == Approx(0.3f));
  CHECK(s->camera_medium() == 0);
  CHECK(s->shapes()[0]->interior_medium == 0);
  CHECK(s->shapes()[0]->exterior_medium == -1);
  CHECK(s->shapes()[1]->emitter >= 0);
  CHECK(s->emitters().size() == 2);  // point light + area light
}

TEST_CASE("yaml: transforms apply scale, then rotate, then translate", "[unit]") {
  auto s = load(kHead + kWhite +
                "shapes:\n"
                "  - {type: triangle, material: white, vertices: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],\n"
                "     transform: {translate: [10, 0, 0], rotate: {axis: [0, 0, 1], angle: 90}, scale: [2, 3, 4]}}\n"
                "  - {type: sphere, center: [1, 0, 0], radius: 0.5, material: white,\n"
                "     transform: {scale: 2, rotate: {axis: [0, 0, 1], angle: 90}, translate: [0, 0, 1]}}\n");
  const TriangleMesh& m = mesh_at(*s, 0);
  REQUIRE(m.positions.size() == 3);
  // (1,0,0) -S-> (2,0,0) -R-> (0,2,0) -T-> (10,2,0); (0,1,0) -> (0,3,0) -> (-3,0,0) -> (7,0,0)
  CHECK(m.positions[0].isApprox(Vec3(10, 2, 0), 1e-5f));
  CHECK(m.positions[1].isApprox(Vec3(7, 0, 0), 1e-5f));
  CHECK(m.positions[2].isApprox(Vec3(10, 0, 4), 1e-5f));
  const auto& sphere = static_cast<const Sphere&>(*s->shapes()[1]);
  CHECK(sphere.center().isApprox(Vec3(0, 2, 1), 1e-5f));
  CHECK(sphere.radius() == Approx(1.0f));
}

TEST_CASE("yaml: mesh normals use the inverse transpose; mirroring keeps the winding consistent", "[unit]") {
  TempDir dir;
  // One triangle in the plane x + y = 1, vertex normals (1, 1, 0)/sqrt2 matching its winding.
  dir.write("tilt.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 0.70710678 0.70710678 0\nf 1//1 2//1 3//1\n");
  auto s = load(kHead + kWhite +
                    "shapes:\n"
                    "  - {type: mesh, file: tilt.obj, material: white, transform: {scale: [2, 1, 1]}}\n"
                    "  - {type: mesh, file: tilt.obj, material: white, smooth: false, transform: {scale: [-1, 1, 1]}}\n",
                dir.path("scene.yaml"));
  const TriangleMesh& a = mesh_at(*s, 0);
  REQUIRE(a.normals.size() == 3);
  // Plane x/2 + y = 1 has normal (0.5, 1, 0); a plain linear map would give (2, 1, 0).
  CHECK(a.normals[0].isApprox(Vec3(0.5f, 1, 0).normalized(), 1e-5f));
  CHECK(a.smooth);
  const TriangleMesh& b = mesh_at(*s, 1);
  CHECK_FALSE(b.smooth);
  REQUIRE(b.triangles.size() == 1);
  const auto& t = b.triangles[0];
  const Vec3 ng = (b.positions[t[1]] - b.positions[t[0]]).cross(b.positions[t[2]] - b.positions[t[0]]);
  CHECK(ng.dot(b.normals[t[0]]) > 0.0f);
  CHECK(b.normals[0].isApprox(Vec3(-1, 1, 0).normalized(), 1e-5f));
}

TEST_CASE("yaml: degenerate mesh triangles are skipped and counted", "[unit]") {
  TempDir dir;
  dir.write("two.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 1 2\n3 0 1 3\n");
  auto s = load(kHead + kWhite + "shapes:\n  - {type: mesh, file: two.ply, material: white}\n", dir.path("scene.yaml"));
  const TriangleMesh& m = mesh_at(*s, 0);
  CHECK(m.triangles.size() == 1);
  CHECK(m.degenerate_skipped == 1);
}

TEST_CASE("yaml: quads and triangles get uvs; textures parse", "[unit]") {
  auto s = load(kHead +
                "materials:\n"
                "  tiles: {type: diffuse, albedo: {checkerboard: {color0: 0.1, color1: [0.9, 0.8, 0.7], scale: 4}}}\n"
                "shapes:\n"
                "  - {type: quad, material: tiles, vertices: [[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]]}\n");
  const TriangleMesh& q = mesh_at(*s, 0);
  REQUIRE(q.uvs.size() == 4);
  CHECK(q.uvs[2] == Vec2(1, 1));
  CHECK(q.triangles.size() == 2);
  CHECK(q.area() == Approx(4.0f));
}

TEST_CASE("yaml: every built-in scene in scenes/ loads", "[unit]") {
  const std::filesystem::path dir = std::filesystem::path(DP_SOURCE_DIR) / "scenes";
  REQUIRE(std::filesystem::is_directory(dir));
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path().string());
    std::unique_ptr<Scene> s;
    REQUIRE_NOTHROW(s = load_scene(entry.path().string()));
    CHECK(!s->emitters().empty());
    CHECK(!s->shapes().empty());
    CHECK(s->bounds().valid());
    ++count;
  }
  CHECK(count >= 5);
  for (const char* name : {"cornell", "cornell_specular", "cornell_glossy", "textured", "concave"})
    CHECK(std::filesystem::exists(dir / (std::string(name) + ".yaml")));
  auto spec = load_scene((dir / "cornell_specular.yaml").string());
  CHECK(spec->caps().has_specular);
  auto textured = load_scene((dir / "textured.yaml").string());
  CHECK(textured->caps().has_env);
  CHECK(textured->caps().has_textures);
}

TEST_CASE("yaml: 'material: none' is an index-matched medium boundary (issue 15)", "[unit]") {
  const std::string media = "media:\n  fog: {type: homogeneous, sigma_a: 0.1, sigma_s: 0.2}\n";
  auto s = load(kHead + media + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: none, interior: fog}\n");
  REQUIRE(s->shapes().size() == 1);
  REQUIRE(s->shapes()[0]->material >= 0);
  const Bsdf& b = *s->bsdfs()[size_t(s->shapes()[0]->material)];
  CHECK(b.lobes() == kNull);
  CHECK(s->caps().has_media);
  // Only on a medium boundary (line 6: the shape), and 'none' cannot be redefined (line 5).
  require_error<ParseError>(kHead + media + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: none}\n", 7,
                            "'material: none' is allowed only on a shape with 'interior' or 'exterior'");
  require_error<ParseError>(kHead + "materials:\n  none: {type: diffuse, albedo: 0.5}\n", 5, "material name 'none' is reserved");
}
