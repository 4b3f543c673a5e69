// Furnace tests of the path tracer: inside a closed diffuse sphere the exact radiance
// is known; the image mean must match it within its standard error.
#include <catch2/catch.hpp>

#include "integrators/integrator.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
integrators::RenderResult render(const scene::Scene& s, int spp, uint64_t seed, int threads, const std::string& set = "") {
  integrators::Settings settings;
  if (!set.empty()) settings.set(set.substr(0, set.find('=')), set.substr(set.find('=') + 1));
  auto pt = integrators::make_integrator("path", settings);
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = threads;
  opt.max_depth = 200;  // truncation bias albedo^200 is far below the noise
  opt.quiet = true;
  return pt->render(s, opt);
}

// Pixels are i.i.d. estimates of the same radiance in a furnace: the standard error of
// the image mean is the pixel standard deviation / sqrt(pixel count).
void check_mean(const core::Image& img, double expected) {
  for (int c = 0; c < 3; ++c) {
    double s = 0, s2 = 0;
    for (const auto& p : img.pixels()) {
      s += double(p[c]);
      s2 += double(p[c]) * double(p[c]);
    }
    const double n = double(img.size()), mean = s / n, var = (s2 / n - mean * mean) * n / (n - 1);
    const double se = std::sqrt(var / n);
    INFO("channel " << c << ": mean " << mean << " expected " << expected << " SE " << se);
    REQUIRE(se > 0);
    REQUIRE(std::abs(mean - expected) < 4.0 * se);  // 4 sigma, fixed seed
  }
}
}  // namespace

TEST_CASE("PT furnace: emissive diffuse sphere of albedo 0.5 gives radiance 1", "[render]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, 32);
  REQUIRE(test::furnace_radiance(0.5f, 0.5f, 0.0f) == Approx(1.0));
  check_mean(render(*s, 16, 1, 2).layers[0].image, 1.0);
  check_mean(render(*s, 16, 2, 2, "nee=false").layers[0].image, 1.0);
}

TEST_CASE("PT furnace: point light at the centre of a sphere of albedo 0.5", "[render]") {
  const float intensity = kPi;  // L = 0.5 * pi / (pi * 0.5) = 1
  const auto s = test::furnace_sphere(0.5f, 0.0f, intensity, 32);
  REQUIRE(test::furnace_radiance(0.5f, 0.0f, intensity) == Approx(1.0));
  check_mean(render(*s, 16, 3, 2).layers[0].image, 1.0);
}

TEST_CASE("PT furnace with a wrong expectation fails (the test can fail)", "[render]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, 32);
  const core::Image img = render(*s, 16, 1, 2).layers[0].image;
  // A 2% error is far outside the 4-sigma band of this render.
  const double mean = img.mean()[0];
  double s2 = 0;
  for (const auto& p : img.pixels()) s2 += (double(p[0]) - mean) * (double(p[0]) - mean);
  const double se = std::sqrt(s2 / double(img.size() - 1) / double(img.size()));
  REQUIRE(std::abs(mean - 1.02) > 4.0 * se);
}

TEST_CASE("PT is deterministic for a seed, whatever the thread count", "[render]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, 24);
  const auto a = render(*s, 4, 7, 2), b = render(*s, 4, 7, 2), c = render(*s, 4, 7, 1), d = render(*s, 4, 8, 2);
  bool differs = false;
  for (size_t i = 0; i < a.layers[0].image.size(); ++i) {
    REQUIRE((a.layers[0].image[i] == b.layers[0].image[i]).all());
    REQUIRE((a.layers[0].image[i] == c.layers[0].image[i]).all());
    differs |= !(a.layers[0].image[i] == d.layers[0].image[i]).all();
  }
  REQUIRE(differs);
  REQUIRE(a.min_spp == 4);
  REQUIRE_FALSE(a.partial);
}
