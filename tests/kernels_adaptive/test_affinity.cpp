// Manzi et al. 2014, Eq. 7 affinities and the choice of the n most similar pixels.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/error.h"
#include "kernels_adaptive/affinity.h"

using namespace dp;
using namespace dp::kernels_adaptive;

namespace {
Features constant_features(int w, int h) {
  Features f;
  f.width = w;
  f.height = h;
  f.normal.assign(size_t(w * h), Vec3(0.5f, 0.5f, 1.0f));
  f.albedo.assign(size_t(w * h), Rgb(0.3f, 0.3f, 0.3f));
  f.depth.assign(size_t(w * h), 0.4f);
  return f;
}
}  // namespace

TEST_CASE("Eq. 7 per feature: thresholded squared distance over sigma^2", "[unit]") {
  CHECK(feature_affinity(0.0, 0.02, 0.01) == 1.0);
  CHECK(feature_affinity(0.019, 0.02, 0.01) == 1.0);  // below tau: no penalty
  CHECK(feature_affinity(0.02 + 1e-4, 0.02, 0.01) == Approx(std::exp(-1.0)).epsilon(1e-12));
  CHECK(feature_affinity(0.0013, 0.001, 0.01) == Approx(std::exp(-3.0)).epsilon(1e-9));
  CHECK(feature_affinity(0.5, 0.0, 0.5) == Approx(std::exp(-2.0)).epsilon(1e-12));
}

TEST_CASE("Eq. 7: omega is the least similar feature's weight (paper defaults)", "[unit]") {
  Features f = constant_features(2, 1);
  const AffinityParams p;  // sigma 0.01; tau normal 0.02, texture 0.001, depth 0.01
  CHECK(affinity(f, 0, 1, p) == 1.0);
  CHECK(affinity_cost(f, 0, 1, p) == 0.0);

  // normal: |(0.15, 0, 0)|^2 = 0.0225 -> (0.0225 - 0.02) / 1e-4 = 25
  // texture: |(0.03, 0.02, 0)|^2 = 0.0013 -> (0.0013 - 0.001) / 1e-4 = 3
  // depth: 0.1^2 = 0.01 -> max(0, 0.01 - 0.01) = 0
  f.normal[1] += Vec3(0.15f, 0.0f, 0.0f);
  f.albedo[1] += Rgb(0.03f, 0.02f, 0.0f);
  f.depth[1] += 0.1f;
  CHECK(affinity_cost(f, 0, 1, p) == Approx(25.0).margin(1e-3));
  CHECK(affinity(f, 0, 1, p) == Approx(std::exp(-25.0)).epsilon(1e-3));
  CHECK(affinity_cost(f, 1, 0, p) == affinity_cost(f, 0, 1, p));  // symmetric in i, j

  // Only texture differs: its factor decides.
  f.normal[1] = f.normal[0];
  CHECK(affinity_cost(f, 0, 1, p) == Approx(3.0).margin(1e-3));
  // Only depth differs, by 0.11: (0.0121 - 0.01) / 1e-4 = 21.
  f.albedo[1] = f.albedo[0];
  f.depth[1] = f.depth[0] + 0.11f;
  CHECK(affinity_cost(f, 0, 1, p) == Approx(21.0).margin(1e-3));
  // Per-feature parameters are used for their own feature only.
  AffinityParams q = p;
  q.sigma_depth = 0.1f;
  CHECK(affinity_cost(f, 0, 1, q) == Approx(0.21).margin(1e-5));
}

TEST_CASE("most_similar: n best by affinity, ties to the nearer pixel then the smaller index", "[unit]") {
  const AffinityParams p;
  Features f = constant_features(5, 5);
  // Constant features: the 4-neighbourhood, nearest first, then by index.
  CHECK(most_similar(f, 12, p) == std::vector<int32_t>{7, 11, 13, 17});
  // Corner: window clipped to the image; (1,1) at distance^2 2 beats (2,0) and (0,2).
  CHECK(most_similar(f, 0, p) == std::vector<int32_t>{1, 5, 6, 2});

  // Pixel 0's clipped 3x3 window: 5 and 10 stay similar; 2 differs in depth only,
  // cost (0.6^2 - 0.01) / 1e-4 = 3500; every other pixel in normal,
  // cost (|(0.5, 0.5, 1)|^2 - 0.02) / 1e-4 = 14800.
  for (int32_t i = 1; i < 25; ++i)
    if (i != 2 && i != 5 && i != 10) f.normal[size_t(i)] = Vec3(0.0f, 0.0f, 0.0f);
  f.depth[2] = 1.0f;
  CHECK(affinity_cost(f, 0, 2, p) == Approx(3500.0).epsilon(1e-5));
  CHECK(affinity_cost(f, 0, 1, p) == Approx(14800.0).epsilon(1e-5));
  // Similar ones first (nearer first), then by cost, then the nearest of the worst.
  CHECK(most_similar(f, 0, p) == std::vector<int32_t>{5, 10, 2, 1});
  AffinityParams three = p;
  three.neighbours = 3;
  CHECK(most_similar(f, 0, three) == std::vector<int32_t>{5, 10, 2});

  AffinityParams big = p;
  big.neighbours = 30;
  CHECK(most_similar(f, 12, big).size() == 24);  // the whole 5x5 window
}

TEST_CASE("affinity parameters are validated", "[unit]") {
  AffinityParams p;
  CHECK_NOTHROW(validate(p));
  p.window = 4;
  CHECK_THROWS_AS(validate(p), ValueError);
  p = {};
  p.sigma_depth = 0.0f;
  CHECK_THROWS_AS(validate(p), ValueError);
  p = {};
  p.tau_texture = -1e-3f;
  CHECK_THROWS_AS(validate(p), ValueError);
  p = {};
  p.neighbours = 0;
  CHECK_THROWS_AS(validate(p), ValueError);
}
