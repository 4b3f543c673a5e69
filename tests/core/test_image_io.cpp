#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"

using namespace dp;
using namespace dp::core;

namespace {
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("dp_test_" + name)).string();
}
}  // namespace

TEST_CASE("EXR multi-layer round trip keeps values and layer names", "[unit]") {
  Image a(5, 3), b(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      a(x, y) = Rgb(float(x), float(y), 0.25f * float(x * y));
      b(x, y) = Rgb(-1.5f, 1e-7f, 3e5f);
    }
  const std::string path = temp_path("layers.exr");
  write_exr(path, {{"", a}, {"dx", b}});
  const auto layers = read_exr_layers(path);
  REQUIRE(layers.size() == 2);
  for (const auto& l : layers) {
    const Image& ref = l.name.empty() ? a : b;
    REQUIRE((l.name.empty() || l.name == "dx"));
    for (size_t i = 0; i < ref.size(); ++i) REQUIRE((l.image[i] == ref[i]).all());
  }
  const Image main = read_exr(path);
  REQUIRE((main(4, 2) == a(4, 2)).all());
  std::remove(path.c_str());
}

TEST_CASE("PNG preview is sRGB encoded and reads back", "[unit]") {
  Image a(2, 1);
  a(0, 0) = Rgb(0.5f, 0.0f, 1.0f);
  a(1, 0) = Rgb(std::nanf(""), 2.0f, 0.214041f);  // NaN written as 0, >1 clamped
  const std::string path = temp_path("preview.png");
  write_png(path, a);
  const Image back = read_ldr(path, true);
  REQUIRE(back(0, 0)[0] == Approx(188.0f / 255.0f).margin(1.0 / 255.0));  // sRGB(0.5) = 0.7354
  REQUIRE(back(1, 0)[0] == 0.0f);
  REQUIRE(back(1, 0)[1] == 1.0f);
  REQUIRE(back(1, 0)[2] == Approx(0.5f).margin(1.0 / 255.0));
  std::remove(path.c_str());
}

TEST_CASE("missing image files raise IoError naming the file", "[unit]") {
  try {
    read_exr("/nonexistent/dir/none.exr");
    FAIL("no exception");
  } catch (const IoError& e) {
    REQUIRE(std::string(e.what()).find("/nonexistent/dir/none.exr") != std::string::npos);
  }
  REQUIRE_THROWS_AS(read_ldr("/nonexistent/none.png"), IoError);
}
