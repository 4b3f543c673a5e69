// Mesh readers: PLY (ascii, binary little/big endian, any scalar type, skipped extra
// elements/properties, meaningful errors) and OBJ (per-corner normals/uvs de-indexed).
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "scene/loaders/mesh_io.h"
#include "test_loader_util.h"

using namespace dp;
using namespace dp::scene;
using Catch::Matchers::Contains;

namespace {

// Test mesh: a unit square at z = 2 (quad, split into 2 triangles) plus one triangle.
const Vec3 kPos[4] = {{0, 0, 2}, {1, 0, 2}, {1, 0.5f, 2}, {0, 0.5f, 2}};
const Vec2 kUv[4] = {{0, 0}, {1, 0}, {1, 1}, {0.25f, 1}};

const char* kHeaderBody =
    "comment written by test_mesh_io\n"
    "element vertex 4\n"
    "property double x\n"
    "property float y\n"
    "property short z\n"
    "property float nx\n"
    "property float ny\n"
    "property float nz\n"
    "property uchar confidence\n"
    "property float s\n"
    "property float t\n"
    "element face 2\n"
    "property list uint8 uint32 vertex_indices\n"
    "property int flags\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "end_header\n";

std::string ascii_ply() {
  std::string s = std::string("ply\nformat ascii 1.0\n") + kHeaderBody;
  for (int i = 0; i < 4; ++i)
    s += std::to_string(kPos[i].x()) + " " + std::to_string(kPos[i].y()) + " 2 0 0 1 255 " +
         std::to_string(kUv[i].x()) + " " + std::to_string(kUv[i].y()) + "\n";
  s += "4 0 1 2 3 7\n3 0 2 3 -1\n0 1\n";
  return s;
}

class BinaryWriter {
 public:
  explicit BinaryWriter(bool big) : m_big(big) {}
  template <typename T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (m_big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    bytes.append(b, sizeof(T));
  }
  std::string bytes;

 private:
  bool m_big;
};

std::string binary_ply(bool big) {
  BinaryWriter w(big);
  w.bytes = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" + kHeaderBody;
  for (int i = 0; i < 4; ++i) {
    w.put<double>(double(kPos[i].x()));
    w.put<float>(kPos[i].y());
    w.put<int16_t>(2);
    w.put<float>(0), w.put<float>(0), w.put<float>(1);
    w.put<uint8_t>(255);
    w.put<float>(kUv[i].x()), w.put<float>(kUv[i].y());
  }
  w.put<uint8_t>(4);
  for (uint32_t i : {0u, 1u, 2u, 3u}) w.put<uint32_t>(i);
  w.put<int32_t>(7);
  w.put<uint8_t>(3);
  for (uint32_t i : {0u, 2u, 3u}) w.put<uint32_t>(i);
  w.put<int32_t>(-1);
  w.put<int32_t>(0), w.put<int32_t>(1);
  return w.bytes;
}

void check_test_mesh(const TriangleMesh& m) {
  REQUIRE(m.positions.size() == 4);
  REQUIRE(m.normals.size() == 4);
  REQUIRE(m.uvs.size() == 4);
  for (size_t i = 0; i < 4; ++i) {
    CHECK(m.positions[i].isApprox(kPos[i], 1e-6f));
    CHECK(m.normals[i].isApprox(Vec3(0, 0, 1), 1e-6f));
    CHECK(m.uvs[i].isApprox(kUv[i], 1e-6f));
  }
  REQUIRE(m.triangles.size() == 3);
  CHECK(m.triangles[0] == std::array<uint32_t, 3>{0, 1, 2});
  CHECK(m.triangles[1] == std::array<uint32_t, 3>{0, 2, 3});
  CHECK(m.triangles[2] == std::array<uint32_t, 3>{0, 2, 3});
}

template <typename E>
void require_mesh_error(const std::string& file, const std::string& phrase, int line = -1) {
  try {
    load_mesh(file);
  } catch (const E& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK_THAT(what, Contains(file));
    CHECK_THAT(what, Contains(phrase));
    if (line >= 0) CHECK(e.line() == line);
    return;
  }
  FAIL("no error was thrown for " + file);
}

}  // namespace

TEST_CASE("ply: ascii, binary little and big endian read the same mesh", "[unit]") {
  TempDir dir;
  SECTION("ascii") { check_test_mesh(*load_mesh(dir.write("a.ply", ascii_ply()))); }
  SECTION("binary_little_endian") { check_test_mesh(*load_ply(dir.write("le.ply", binary_ply(false)))); }
  SECTION("binary_big_endian") { check_test_mesh(*load_ply(dir.write("be.PLY", binary_ply(true)))); }
}

TEST_CASE("ply: CRLF headers and positions-only meshes", "[unit]") {
  TempDir dir;
  auto m = load_ply(dir.write("crlf.ply", "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty int x\r\n"
                                          "property int y\r\nproperty int z\r\nelement face 1\r\n"
                                          "property list uchar int vertex_index\r\nend_header\r\n"
                                          "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 2 1 0\r\n"));
  CHECK(m->positions.size() == 3);
  CHECK(m->normals.empty());
  CHECK(m->uvs.empty());
  REQUIRE(m->triangles.size() == 1);
  CHECK(m->triangles[0] == std::array<uint32_t, 3>{2, 1, 0});
}

TEST_CASE("ply: malformed files give errors naming the file and problem", "[unit]") {
  TempDir dir;
  const std::string good_header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  require_mesh_error<IoError>(dir.path("missing.ply"), "cannot open");
  require_mesh_error<ParseError>(dir.write("magic.ply", "hello\n"), "not a PLY file", 1);
  require_mesh_error<ParseError>(dir.write("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty flot x\n"),
                                 "unknown property type 'flot'", 4);
  require_mesh_error<ParseError>(dir.write("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"),
                                 "unknown PLY format", 2);
  require_mesh_error<ParseError>(dir.write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), "no end_header");
  // Line 12 of the file holds the bad token.
  require_mesh_error<ParseError>(dir.write("token.ply", good_header + "0 0 0\n1 0 0\n0 abc 0\n3 0 1 2\n"),
                                 "expected a number, got 'abc'", 12);
  require_mesh_error<ParseError>(dir.write("range.ply", good_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), "out of range");
  require_mesh_error<ParseError>(dir.write("two.ply", good_header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "at least 3");
  require_mesh_error<ParseError>(dir.write("short.ply", good_header + "0 0 0\n1 0 0\n"), "unexpected end of file");
  std::string bin = binary_ply(false);
  require_mesh_error<ParseError>(dir.write("trunc.ply", bin.substr(0, bin.size() - 10)), "unexpected end of file");
  require_mesh_error<ParseError>(
      dir.write("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n\x01\x02"),
      "more than the file holds");
  require_mesh_error<ParseError>(
      dir.write("nofaces.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n0 0 0\n"),
      "no faces");
  require_mesh_error<IoError>(dir.write("mesh.off", "OFF\n"), "unsupported mesh format");
}

TEST_CASE("obj: per-corner normals and uvs are de-indexed into vertices", "[unit]") {
  TempDir dir;
  // Two triangles share positions 1 and 2 but use different normals there.
  const std::string file = dir.write("corner.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                     "vt 0 0\nvt 1 0\nvt 0 1\n"
                                     "vn 0 0 1\nvn 0 -2 0\n"
                                     "f 1/1/1 2/2/1 3/3/1\n"
                                     "g second\nf 2/2/2 1/1/2 4/3/2\n");
  auto m = load_mesh(file);
  REQUIRE(m->triangles.size() == 2);
  REQUIRE(m->positions.size() == 6);
  REQUIRE(m->normals.size() == 6);
  REQUIRE(m->uvs.size() == 6);
  const Vec3 face_normal[2] = {Vec3(0, 0, 1), Vec3(0, -1, 0)};
  const Vec3 corner_pos[2][3] = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                 {Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 1)}};
  const Vec2 corner_uv[2][3] = {{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, {Vec2(1, 0), Vec2(0, 0), Vec2(0, 1)}};
  for (size_t f = 0; f < 2; ++f)
    for (size_t c = 0; c < 3; ++c) {
      const uint32_t v = m->triangles[f][c];
      CHECK(m->positions[v].isApprox(corner_pos[f][c]));
      CHECK(m->normals[v].isApprox(face_normal[f]));  // normalized on load
      CHECK(m->uvs[v].isApprox(corner_uv[f][c]));
    }
}

TEST_CASE("obj: polygons are triangulated, partial normals dropped, bad indices rejected", "[unit]") {
  TempDir dir;
  auto quad = load_obj(dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  CHECK(quad->triangles.size() == 2);
  CHECK(quad->positions.size() == 4);
  auto mixed = load_obj(dir.write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n"
                                               "f 1//1 2//1 3//1\nf 1 2 4\n"));
  CHECK(mixed->normals.empty());
  CHECK(mixed->positions.size() == 4);
  CHECK(mixed->triangles.size() == 2);
  require_mesh_error<IoError>(dir.path("none.obj"), "cannot open");
  require_mesh_error<ParseError>(dir.write("empty.obj", "v 0 0 0\n"), "no faces");
  CHECK_THROWS_AS(load_obj(dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")), ParseError);
}

TEST_CASE("mesh files from ../shared/scenes load", "[unit]") {
  const std::filesystem::path root = "../shared/scenes/meshes";
  if (!std::filesystem::is_directory(root)) {
    WARN("skipped: " << root << " is not available");
    return;
  }
  auto res4 = load_ply((root / "stanford/bun_zipper_res4.ply").string());  // ascii
  CHECK(res4->positions.size() == 453);
  CHECK(res4->triangles.size() == 948);
  auto bunny = load_ply((root / "mitsuba-data/bunny.ply").string());  // binary little endian
  CHECK(bunny->positions.size() == 35947);
  CHECK(bunny->triangles.size() == 69451);
  auto teapot = load_obj((root / "common-3d-test-models/teapot.obj").string());
  CHECK(teapot->triangles.size() > 1000);
  for (const auto& t : teapot->triangles)
    for (uint32_t i : t) REQUIRE(i < teapot->positions.size());
  auto spot = load_obj((root / "common-3d-test-models/spot.obj").string());
  CHECK(spot->uvs.size() == spot->positions.size());
  CHECK(!spot->uvs.empty());
}
