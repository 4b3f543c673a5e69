// Issue 18, "extreme values are errors, not aborts": scene inputs that used to abort in
// Embree (coordinates near 1e17 and beyond), overflow an integer (a checkerboard scale of
// 1e30), fail a huge allocation (a 65536 x 65536 film), pass as numbers (hex) or produce
// huge or multi-line messages (a 5 MB file name, a folder given as a mesh, raw bytes of a
// corrupt PLY, multi-MB values) are each a short one-line "file:line: problem" error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "scene/loaders/loader.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"
#include "scene/bsdf/texture.h"
#include "test_loader_util.h"

using namespace dp;
using namespace dp::scene;

namespace {

const std::string kYamlPath = "mem/extreme.yaml";
const std::string kXmlPath = "mem/extreme.xml";

// Lines 1-5 of every YAML document here; test-specific text starts at line 6.
const std::string kYamlHead =
    "version: 1\n"
    "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n"
    "lights: [{type: point, position: [0, 0, 4], intensity: 1}]\n"
    "materials:\n"
    "  white: {type: diffuse, albedo: 0.5}\n";

const std::string& kXmlHead = kMitsubaHead;

std::unique_ptr<Scene> load_yaml(const std::string& t, const std::string& p) { return load_scene_yaml_string(t, p); }
std::unique_ptr<Scene> load_xml(const std::string& t, const std::string& p) { return load_scene_mitsuba_string(t, p); }

template <typename E>
void yaml_error(const std::string& body, int line, const std::string& phrase) {
  require_load_error<E>(load_yaml, kYamlHead + body, line, phrase, kYamlPath);
}
template <typename E>
void xml_error(const std::string& body, int line, const std::string& phrase) {
  require_load_error<E>(load_xml, kXmlHead + body + "</scene>\n", line, phrase, kXmlPath);
}

// Loading must fail with a dp::Error whose message is one short line naming path:line.
template <typename Load>
void short_error(Load load, const std::string& text, const std::string& path, int line, const std::string& phrase) {
  try {
    load(text, path);
  } catch (const Error& e) {
    const std::string what = e.what();
    INFO(what.substr(0, 400));
    CHECK(what.rfind(path + ":" + std::to_string(line) + ": ", 0) == 0);
    CHECK_THAT(what, Catch::Matchers::Contains(phrase));
    CHECK(what.size() < 400);
    CHECK(std::none_of(what.begin(), what.end(), [](char c) { return (unsigned char)c < 0x20; }));
    return;
  } catch (const std::exception& e) {
    FAIL("not a dp::Error: " + std::string(e.what()).substr(0, 300));
  }
  FAIL("no error was thrown");
}

std::string sphere(const std::string& center, const std::string& radius) {
  return "shapes:\n  - {type: sphere, center: " + center + ", radius: " + radius + ", material: white}\n";
}

}  // namespace

TEST_CASE("extreme: YAML numbers beyond the scene limit are ValueErrors at their line", "[unit]") {
  yaml_error<ValueError>(sphere("[0, 0, 0]", "1e30"), 7, "'radius': 1e30 is beyond the scene limit");
  yaml_error<ValueError>(sphere("[0, 1e17, 0]", "1"), 7, "'center': 1e17 is beyond the scene limit");
  yaml_error<ValueError>(sphere("[0, 0, -2e12]", "1"), 7, "beyond the scene limit");
  yaml_error<ValueError>("shapes:\n  - {type: quad, material: white,\n     vertices: [[0,0,0],[1,0,0],[1,1,0],[0,1,1e18]]}\n",
                         8, "'vertices': 1e18 is beyond the scene limit");
  REQUIRE_THROWS_AS(load_yaml("version: 1\ncamera: {position: [0, 0, 1e17], look_at: [0, 0, 0], fov: 40, resolution: [8, 8]}\n",
                              kYamlPath),
                    ValueError);
  // At the limit: loads.
  CHECK(load_yaml(kYamlHead + sphere("[0, 0, -5e11]", "1e11"), kYamlPath)->shapes().size() == 1);
}

TEST_CASE("extreme: YAML shapes whose transform carries them beyond the limit are ValueErrors", "[unit]") {
  yaml_error<ValueError>("shapes:\n  - {type: quad, material: white, vertices: [[0,0,0],[2,0,0],[2,2,0],[0,2,0]],\n"
                         "     transform: {scale: 1e11, translate: [1e12, 0, 0]}}\n",
                         7, "beyond the scene limit");
  yaml_error<ValueError>("shapes:\n  - {type: sphere, center: [1e11, 0, 0], radius: 1e11, material: white,\n"
                         "     transform: {scale: 1e11}}\n",
                         7, "sphere reaches beyond the scene limit");
}

TEST_CASE("extreme: hexadecimal and other ill-formed numbers are not numbers", "[unit]") {
  yaml_error<ParseError>(sphere("[0, 0, 0]", "0x10"), 7, "'radius': expected a number, got '0x10'");
  yaml_error<ParseError>(sphere("[0, 0, 0]", "1e"), 7, "expected a number, got '1e'");
  yaml_error<ParseError>(sphere("[0x1p3, 0, 0]", "1"), 7, "expected a number, got '0x1p3'");
  xml_error<ParseError>("<shape type=\"sphere\"><float name=\"radius\" value=\"0x10\"/></shape>\n", 8, "'0x10' is not a number");
  xml_error<ParseError>("<shape type=\"sphere\"><point name=\"center\" value=\"0x1 0 0\"/></shape>\n", 8,
                        "'0x1' is not a number");
  // Ordinary spellings still are numbers.
  CHECK(load_yaml(kYamlHead + sphere("[+1, -.5, 2.]", "1.5e-1"), kYamlPath)->shapes().size() == 1);
}

TEST_CASE("extreme: Mitsuba numbers and transformed shapes beyond the limit are ValueErrors", "[unit]") {
  xml_error<ValueError>("<shape type=\"sphere\"><float name=\"radius\" value=\"1e30\"/></shape>\n", 8,
                        "'1e30' is beyond the scene limit");
  xml_error<ValueError>("<shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"1e17\" z=\"0\"/></shape>\n", 8,
                        "beyond the scene limit");
  xml_error<ValueError>("<shape type=\"rectangle\"><transform name=\"to_world\">\n"
                        "<matrix value=\"18446744073709551616 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1\"/></transform></shape>\n",
                        9, "'18446744073709551616' is beyond the scene limit");
  // Each number within the limit, their product not: the vertices after to_world are checked.
  xml_error<ValueError>("<shape type=\"rectangle\"><transform name=\"to_world\">\n"
                        "<scale value=\"1e11\"/><scale value=\"1e11\"/></transform></shape>\n",
                        8, "beyond the scene limit");
  xml_error<ValueError>("<shape type=\"sphere\"><float name=\"radius\" value=\"1e11\"/><transform name=\"to_world\">\n"
                        "<scale value=\"1e11\"/></transform></shape>\n",
                        8, "sphere reaches beyond the scene limit");
  xml_error<ValueError>("<emitter type=\"point\"><transform name=\"to_world\"><translate x=\"1e12\"/>\n"
                        "<scale value=\"1e11\"/></transform></emitter>\n",
                        8, "light position beyond the scene limit");
}

TEST_CASE("extreme: a checkerboard scale of 1e30 is an error, and lookups far out stay defined", "[unit]") {
  yaml_error<ValueError>("  chk: {type: diffuse, albedo: {checkerboard: {color0: 0, color1: 1, scale: [1e30, 1e30]}}}\n", 6,
                         "'scale': 1e30 is beyond the scene limit");
  xml_error<ValueError>(
      "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"checkerboard\">\n"
      "<float name=\"uscale\" value=\"1e30\"/></texture></bsdf></shape>\n",
      9, "'1e30' is beyond the scene limit");
  // The lookup itself: uv * scale far beyond any integer type.
  const CheckerboardTexture big(Rgb::Zero(), Rgb::Ones(), Vec2(1e12f, 1e12f));
  for (const Vec2& uv : {Vec2(0.3f, 0.7f), Vec2(1e7f, -1e7f), Vec2(3e38f, 3e38f)}) {
    const Rgb c = big.eval(uv);
    CHECK((c[0] == 0.0f || c[0] == 1.0f));
  }
  const CheckerboardTexture unit(Rgb::Zero(), Rgb::Ones(), Vec2(1, 1));
  CHECK(unit.eval(Vec2(0.5f, 0.5f))[0] == 0.0f);   // (0, 0): even
  CHECK(unit.eval(Vec2(1.5f, 0.5f))[0] == 1.0f);   // (1, 0): odd
  CHECK(unit.eval(Vec2(-0.5f, 0.5f))[0] == 1.0f);  // (-1, 0): odd
  CHECK(unit.eval(Vec2(-0.5f, -0.5f))[0] == 0.0f); // (-1, -1): even
}

TEST_CASE("extreme: a 65536 x 65536 film is an error at its line, not an allocation failure", "[unit]") {
  require_load_error<ValueError>(
      load_yaml, "version: 1\ncamera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, resolution: [65536, 65536]}\n", 2,
      "at most 67108864", kYamlPath);
  require_load_error<ValueError>(
      load_xml,
      "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\">\n"
      "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"65536\"/><integer name=\"height\" value=\"65536\"/></film>\n"
      "  </sensor>\n</scene>\n",
      3, "at most 67108864", kXmlPath);
}

TEST_CASE("extreme: a 5 MB file name is a short error at the scene line", "[unit]") {
  const std::string name(5'000'000, 'a');
  short_error(load_yaml, kYamlHead + "shapes:\n  - {type: mesh, material: white, file: " + name + ".ply}\n", kYamlPath, 7,
              "File name too long");
  short_error(load_xml, kXmlHead + "<shape type=\"ply\">\n<string name=\"filename\" value=\"" + name + ".ply\"/></shape>\n</scene>\n",
              kXmlPath, 9, "File name too long");
}

TEST_CASE("extreme: a folder where a mesh file should be is 'is a directory'", "[unit]") {
  const TempDir dir;
  for (const char* folder : {"mesh.ply", "mesh.obj", "mesh.serialized"}) {
    std::filesystem::create_directories(dir.path(folder));
    const std::string type = std::filesystem::path(folder).extension().string().substr(1);
    if (type != "serialized")
      short_error(load_yaml, kYamlHead + "shapes:\n  - {type: mesh, material: white, file: " + dir.path(folder) + "}\n",
                  kYamlPath, 7, "is a directory");
    short_error(load_xml,
                kXmlHead + "<shape type=\"" + type + "\">\n<string name=\"filename\" value=\"" + dir.path(folder) +
                    "\"/></shape>\n</scene>\n",
                kXmlPath, 9, "is a directory");
  }
}

TEST_CASE("extreme: raw bytes of a corrupt PLY are not pasted into the message", "[unit]") {
  const TempDir dir;
  std::string junk;
  for (int i = 0; i < 500; ++i) junk += char((i * 37 + 11) % 256 == '\n' ? 'x' : (i * 37 + 11) % 256);
  const std::string header_junk = dir.write("header.ply", "ply\nformat binary_little_endian 1.0\n" + junk + "\nend_header\n");
  const std::string element_junk = dir.write("element.ply", "ply\nformat ascii 1.0\nelement " + junk + "\nend_header\n");
  const std::string body_junk = dir.write(
      "body.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 " +
                      std::string(300, '7') + "z\n0 1 0\n3 0 1 2\n");
  for (const std::string& file : {header_junk, element_junk, body_junk}) {
    short_error(load_yaml, kYamlHead + "shapes:\n  - {type: mesh, material: white, file: " + file + "}\n", kYamlPath, 7,
                "invalid mesh");
    short_error(load_xml, kXmlHead + "<shape type=\"ply\">\n<string name=\"filename\" value=\"" + file + "\"/></shape>\n</scene>\n",
                kXmlPath, 9, "invalid mesh");
  }
}

TEST_CASE("extreme: multi-MB values are quoted in at most ~60 characters", "[unit]") {
  const std::string big(3'000'000, '9');
  const std::string word(3'000'000, 'w');
  short_error(load_yaml, kYamlHead + sphere("[0, 0, 0]", word), kYamlPath, 7, "expected a number, got 'www");
  short_error(load_yaml, kYamlHead + sphere("[0, 0, 0]", big), kYamlPath, 7, "not a finite number (999");
  short_error(load_yaml, kYamlHead + "shapes:\n  - {type: " + word + "}\n", kYamlPath, 7, "unknown shape type");
  short_error(load_yaml, kYamlHead + word + ": 1\n", kYamlPath, 6, "malformed YAML");  // yaml-cpp: key too long
  short_error(load_yaml, kYamlHead + word.substr(0, 1000) + ": 1\n", kYamlPath, 6, "unknown key 'www");
  short_error(load_yaml, kYamlHead + "shapes:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: x" + word + "}\n",
              kYamlPath, 7, "undefined material 'xww");
  short_error(load_xml, kXmlHead + "<shape type=\"sphere\"><float name=\"radius\" value=\"" + word + "\"/></shape>\n</scene>\n",
              kXmlPath, 8, "is not a number");
  short_error(load_xml, kXmlHead + "<shape type=\"" + word + "\"/>\n</scene>\n", kXmlPath, 8, "unsupported shape type");
  short_error(load_xml, kXmlHead + "<shape type=\"sphere\"><ref id=\"" + word + "\"/></shape>\n</scene>\n", kXmlPath, 8,
              "undefined id");
}
