// Bitmap and checkerboard textures: orientation (uv (0,0) = bottom-left), bilinear
// interpolation between texel centres, repeat wrapping; PNG round trip via core I/O.
#include <catch2/catch.hpp>
#include <filesystem>

#include "core/image_io.h"
#include "scene/bsdf/texture.h"

using namespace dp;
using namespace dp::scene;

TEST_CASE("bitmap texture: orientation, bilinear lookup and wrapping", "[unit]") {
  // 4 x 2 image; row 0 is the top row. Values 0/1 survive the 8-bit sRGB round trip.
  core::Image img(4, 2, Rgb::Zero());
  img(0, 1) = Rgb(1, 0, 0);  // bottom-left texel
  img(3, 0) = Rgb(0, 1, 0);  // top-right texel
  img(1, 0) = Rgb(0, 0, 1);
  const auto dir = std::filesystem::temp_directory_path() / "dp_test_texture";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "tex.png").string();
  core::write_png(path, img);
  const BitmapTexture tex(path);
  REQUIRE(tex.image().width() == 4);
  REQUIRE(tex.image().height() == 2);
  const auto near = [](const Rgb& a, const Rgb& b) { return (a - b).abs().maxCoeff() < 1e-5f; };
  // Texel centres: uv = ((i + 0.5) / 4, 1 - (j + 0.5) / 2).
  CHECK(near(tex.eval(Vec2(0.125f, 0.25f)), Rgb(1, 0, 0)));
  CHECK(near(tex.eval(Vec2(0.875f, 0.75f)), Rgb(0, 1, 0)));
  CHECK(near(tex.eval(Vec2(0.375f, 0.75f)), Rgb(0, 0, 1)));
  // Bilinear: halfway between the bottom-left (red) and its right neighbour (black).
  CHECK(near(tex.eval(Vec2(0.25f, 0.25f)), Rgb(0.5f, 0, 0)));
  // Halfway between bottom-left (red) and top-left (black) vertically.
  CHECK(near(tex.eval(Vec2(0.125f, 0.5f)), Rgb(0.5f, 0, 0)));
  // Centre of the 2x2 block of texels (0..1, 0..1): (red + blue) / 4.
  CHECK(near(tex.eval(Vec2(0.25f, 0.5f)), Rgb(0.25f, 0, 0.25f)));
  // Repeat wrapping: u = 0 is halfway between texel 3 and texel 0 of the same row.
  CHECK(near(tex.eval(Vec2(0.0f, 0.25f)), Rgb(0.5f, 0, 0)));
  CHECK(near(tex.eval(Vec2(1.0f, 0.25f)), Rgb(0.5f, 0, 0)));
  CHECK(near(tex.eval(Vec2(2.125f, -0.75f)), Rgb(1, 0, 0)));
  CHECK(near(tex.eval(Vec2(-0.125f, 0.75f)), Rgb(0, 1, 0)));
  // v wraps too: v = 0 is halfway between the bottom row and the top row.
  CHECK(near(tex.eval(Vec2(0.125f, 0.0f)), Rgb(0.5f, 0, 0)));
  CHECK(near(tex.mean(), Rgb(1, 1, 1) / 8.0f));
  CHECK(near(tex.max(), Rgb(1, 1, 1)));
  // Scale and the in-memory constructor.
  const BitmapTexture scaled(path, 2.0f);
  CHECK(near(scaled.eval(Vec2(0.125f, 0.25f)), Rgb(2, 0, 0)));
  const BitmapTexture mem(img);
  CHECK(near(mem.eval(Vec2(0.875f, 0.75f)), Rgb(0, 1, 0)));
  std::filesystem::remove_all(dir);
  CHECK_THROWS(BitmapTexture((dir / "missing.png").string()));
}

TEST_CASE("checkerboard texture pattern", "[unit]") {
  const CheckerboardTexture c(Rgb(0.1f, 0.1f, 0.1f), Rgb(0.9f, 0.9f, 0.9f), Vec2(4, 2));
  CHECK(c.eval(Vec2(0.1f, 0.1f))[0] == Approx(0.1f));   // (0, 0): even
  CHECK(c.eval(Vec2(0.3f, 0.1f))[0] == Approx(0.9f));   // (1, 0): odd
  CHECK(c.eval(Vec2(0.3f, 0.6f))[0] == Approx(0.1f));   // (1, 1): even
  CHECK(c.eval(Vec2(0.1f, 0.6f))[0] == Approx(0.9f));   // (0, 1): odd
  CHECK(c.eval(Vec2(-0.1f, 0.1f))[0] == Approx(0.9f));  // (-1, 0): odd
  CHECK(c.eval(Vec2(-0.1f, -0.1f))[0] == Approx(0.1f)); // (-1, -1): even
  CHECK(c.mean()[0] == Approx(0.5f));
  CHECK(c.max()[0] == Approx(0.9f));
}
