#include <catch2/catch.hpp>

#include "core/distribution.h"
#include "core/rng.h"

using namespace dp;
using namespace dp::core;

TEST_CASE("Distribution1D discrete frequencies follow the weights", "[stat]") {
  const std::vector<float> w{1, 0, 3, 6};
  Distribution1D d(w);
  Rng rng(5, 0);
  const int n = 100000;
  std::vector<int> count(4, 0);
  for (int i = 0; i < n; ++i) {
    float pmf;
    count[d.sample_discrete(rng.uniform(), pmf)]++;
  }
  REQUIRE(count[1] == 0);
  for (int i = 0; i < 4; ++i) {
    const double p = double(w[size_t(i)]) / 10.0;
    REQUIRE(d.pmf(size_t(i)) == Approx(p));
    // binomial standard deviation, 5 sigma
    REQUIRE(std::abs(count[size_t(i)] - n * p) <= 5 * std::sqrt(n * p * (1 - p)) + 1e-9);
  }
}

TEST_CASE("Distribution2D pdf matches sampling density and integrates to one", "[unit]") {
  const int w = 8, h = 4;
  std::vector<float> weights(size_t(w * h));
  for (int i = 0; i < w * h; ++i) weights[size_t(i)] = float((i * 7) % 5);
  Distribution2D d(weights, w, h);
  double integral = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) integral += double(d.pdf(Vec2((x + 0.5f) / w, (y + 0.5f) / h))) / (w * h);
  REQUIRE(integral == Approx(1.0).epsilon(1e-5));
  Rng rng(2, 0);
  for (int i = 0; i < 1000; ++i) {
    float pdf;
    const Vec2 p = d.sample(rng.uniform2(), pdf);
    REQUIRE(pdf > 0);
    REQUIRE(pdf == Approx(d.pdf(p)).epsilon(1e-4));
  }
}
