// The photon grid's range queries against brute force: every point within r reported
// exactly once, none outside, at the build radius, below it (the 8-cell path) and above it
// (the wide path G-PM's footprint kernels use, including a radius with more cells than
// hash buckets).
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "core/rng.h"
#include "integrators/vcm/photon_grid.h"

using namespace dp;

TEST_CASE("photon grid: range queries of any radius match brute force, each point once", "[unit]") {
  core::Rng rng(5, 9);
  std::vector<Vec3> pts;
  for (int i = 0; i < 2000; ++i) pts.emplace_back(rng.uniform(), rng.uniform(), 0.1f * rng.uniform());
  for (int i = 0; i < 200; ++i) pts.emplace_back(0.5f, 0.5f, 0.05f);  // coincident points
  const float r0 = 0.02f;
  integrators::PhotonGrid grid;
  grid.build(pts, r0);
  REQUIRE(grid.order().size() == pts.size());
  int64_t checked = 0;
  for (float r : {0.5f * r0, r0, 3.0f * r0, 40.0f * r0}) {
    for (int q = 0; q < 200; ++q) {
      const Vec3 c(1.2f * rng.uniform() - 0.1f, 1.2f * rng.uniform() - 0.1f, 0.1f * rng.uniform());
      std::vector<uint32_t> found;
      grid.query(c, r, [&](uint32_t k) { found.push_back(grid.order()[k]); });
      std::vector<uint32_t> expect;
      for (uint32_t i = 0; i < pts.size(); ++i)
        if ((pts[i] - c).squaredNorm() <= r * r) expect.push_back(i);
      std::sort(found.begin(), found.end());
      INFO("radius " << r << ", query " << q);
      CHECK(found == expect);  // equal sorted lists: no duplicate, none missing or extra
      checked += int64_t(expect.size());
    }
  }
  CHECK(checked > 1000);
}
