#include <catch2/catch.hpp>

#include "core/rng.h"

using namespace dp::core;

TEST_CASE("rng streams are reproducible and distinct", "[unit]") {
  Rng a(42, 3), b(42, 3), c(42, 4), d(43, 3);
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 1000; ++i) {
    const float x = a.uniform();
    REQUIRE(x == b.uniform());
    REQUIRE(x >= 0.0f);
    REQUIRE(x < 1.0f);
    same_c += x == c.uniform();
    same_d += x == d.uniform();
  }
  REQUIRE(same_c < 5);
  REQUIRE(same_d < 5);
}

TEST_CASE("rng uniform mean and variance are those of U(0,1)", "[unit]") {
  Rng r(1, 0);
  const int n = 200000;
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.uniform_double();
    s += x;
    s2 += x * x;
  }
  // Standard error of the mean of U(0,1) is sqrt(1/12/n); allow 5 sigma.
  REQUIRE(std::abs(s / n - 0.5) < 5.0 * std::sqrt(1.0 / 12.0 / n));
  REQUIRE(std::abs(s2 / n - 1.0 / 3.0) < 5.0 * std::sqrt(4.0 / 45.0 / n));
}
