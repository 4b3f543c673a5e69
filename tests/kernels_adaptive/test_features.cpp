// render_features: primary-hit feature buffers normalised to [0, 1] (Manzi et al. 2014,
// Sec. 4-5), deterministic for any thread count.
#include <algorithm>
#include <catch2/catch.hpp>

#include "core/error.h"
#include "kernels_adaptive/features.h"
#include "kernels_adaptive/pair_kernel.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::kernels_adaptive;

namespace {
bool identical(const Features& a, const Features& b) {
  if (a.width != b.width || a.height != b.height) return false;
  for (size_t i = 0; i < a.pixels(); ++i)
    if ((a.normal[i].array() != b.normal[i].array()).any() || (a.albedo[i] != b.albedo[i]).any() ||
        a.depth[i] != b.depth[i])
      return false;
  return true;
}
}  // namespace

TEST_CASE("render_features on the lit box: deterministic for any thread count", "[unit]") {
  // Enough rows and rays per row that every worker of a multi-threaded run gets rows
  // (a stream tied to the worker instead of the row then changes the image).
  const auto scene = test::lit_box(nullptr, nullptr, 64);
  const Features f1 = render_features(*scene, 8, 7, 1);
  REQUIRE(f1.width == 64);
  REQUIRE(f1.height == 64);
  REQUIRE(f1.pixels() == 64 * 64);
  for (int threads : {2, 3, 4, 0}) {
    INFO("threads " << threads);
    CHECK(identical(f1, render_features(*scene, 8, 7, threads)));
  }
  // The seed drives the jitter: another seed moves pixels on edges.
  CHECK_FALSE(identical(f1, render_features(*scene, 8, 8, 2)));
}

TEST_CASE("render_features: each feature spans [0, 1] and sees the box's structure", "[unit]") {
  const auto scene = test::lit_box(nullptr, nullptr, 32);
  const Features f = render_features(*scene, 2, 1, 2);
  float nlo = 1, nhi = 0, alo = 1, ahi = 0;
  for (size_t i = 0; i < f.pixels(); ++i) {
    nlo = std::min(nlo, f.normal[i].minCoeff());
    nhi = std::max(nhi, f.normal[i].maxCoeff());
    alo = std::min(alo, f.albedo[i].minCoeff());
    ahi = std::max(ahi, f.albedo[i].maxCoeff());
  }
  const auto [dlo, dhi] = std::minmax_element(f.depth.begin(), f.depth.end());
  CHECK(nlo == 0.0f);
  CHECK(nhi == 1.0f);
  CHECK(alo == 0.0f);  // the light has no BSDF: albedo 0
  CHECK(ahi == 1.0f);
  CHECK(*dlo == 0.0f);
  CHECK(*dhi == 1.0f);
  // The red left wall (albedo 0.7, 0.1, 0.1) at the left edge, mid height; white
  // (0.7, 0.7, 0.7) floor at the bottom centre: same red channel, different green.
  const Rgb left = f.albedo[size_t(16 * 32 + 0)], floor = f.albedo[size_t(31 * 32 + 16)];
  CHECK(left[0] == Approx(floor[0]).margin(1e-6));
  CHECK(left[1] < floor[1] - 0.5f);
  // The left wall and the floor face different ways.
  CHECK((f.normal[size_t(16 * 32 + 0)] - f.normal[size_t(31 * 32 + 16)]).squaredNorm() > 0.2f);
  // The features feed adaptive_kernel: every pixel gets its n = 4 partners.
  const PairKernel k = adaptive_kernel(f, {});
  CHECK(k.rows.size() == size_t(4 * 32 * 32));
}

TEST_CASE("render_features and normalize_features reject bad input", "[unit]") {
  const auto scene = test::lit_box(nullptr, nullptr, 8);
  CHECK_THROWS_AS(render_features(*scene, 0, 1, 1), ValueError);
  Features f;
  f.width = 2;
  f.height = 2;
  f.normal.assign(4, Vec3::Zero());
  f.albedo.assign(3, Rgb::Zero());
  f.depth.assign(4, 0.0f);
  CHECK_THROWS_AS(normalize_features(f), ValueError);
  f.albedo.assign(4, Rgb::Constant(0.3f));
  normalize_features(f);  // constant features map to 0
  CHECK(f.albedo[2][0] == 0.0f);
}
