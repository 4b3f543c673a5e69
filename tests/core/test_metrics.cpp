#include <catch2/catch.hpp>

#include "core/metrics.h"

using namespace dp;
using namespace dp::core;

TEST_CASE("metrics match hand-computed values", "[unit]") {
  Image r(2, 1, Rgb(1, 1, 1)), x(2, 1, Rgb(1, 1, 1));
  x(0, 0) = Rgb(2, 1, 1);  // one channel off by 1
  REQUIRE(mse(x, r) == Approx(1.0 / 6.0));
  REQUIRE(relmse(x, r) == Approx(1.0 / (1.0 + 1e-3) / 6.0));
  REQUIRE(mse(x, r, 1) == Approx(0.0));  // worst pixel discarded
  x(1, 0) = Rgb(std::nanf(""), 0, 0);
  const ErrorReport rep = compare(x, r);
  REQUIRE(rep.nonfinite == 1);
  REQUIRE(rep.mse == Approx(1.0 / 3.0));
  REQUIRE(rep.mean_ratio[1] == Approx(0.5));
}
