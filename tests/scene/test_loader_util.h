// Temporary folder for loader tests: files written into it are removed with it.
#pragma once

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    m_dir = std::filesystem::temp_directory_path() / ("dp_loader_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(m_dir);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_dir, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path(const std::string& name) const { return (m_dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream out(m_dir / name, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return path(name);
  }

 private:
  std::filesystem::path m_dir;
};

// Loads `text` with `load(text, path)` and requires a typed error E whose one-line
// message starts with "path:line: " and contains `phrase` (shared by the YAML and
// Mitsuba front-end tests).
template <typename E, typename Load>
void require_load_error(Load load, const std::string& text, int line, const std::string& phrase,
                        const std::string& path) {
  INFO(text);
  try {
    load(text, path);
  } catch (const E& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.line() == line);
    CHECK_THAT(what, Catch::Matchers::Contains(path + ":" + std::to_string(line) + ": "));
    CHECK_THAT(what, Catch::Matchers::Contains(phrase));
    CHECK(what.find('\n') == std::string::npos);
    return;
  }
  FAIL("no error was thrown");
}

// Lines 1-7 of a valid Mitsuba scene (an 8x6 perspective sensor and a point light);
// tests append their elements from line 8 on and close it with </scene>.
inline const std::string kMitsubaHead =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"40\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0,0,5\" target=\"0,0,0\" up=\"0,1,0\"/></transform>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"6\"/></film>\n"
    "  </sensor>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"4\"/></emitter>\n";

