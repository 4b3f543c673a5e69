// Unbiasedness of G-PT against the reference PT on a small lit box with a glossy and a
// diffuse sphere: (1) block sums of the dx / dy layers equal block sums of differences of
// PT's pixel expectations, (2) the mean of the L2 reconstruction equals PT's image mean.
// Welch t-tests over independent renders (fixed seeds), Sidak-corrected over blocks;
// thresholds come from the estimators' sample variances. A 10% scaled gradient total and
// a x2 or x0.5 per-pair splat factor must fail.
#include <catch2/catch.hpp>
#include <cstdio>

#include "tests/integrators/gpt_unbiased_support.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

using namespace dp::test;

TEST_CASE("G-PT gradients and L2 mean agree with PT in expectation", "[stat]") {
  const auto s = test::lit_box(
      scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                  scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
      nullptr, kRes);
  const Blocks g = stats(*s, "gpt", 16, 1000), p = stats(*s, "path", 64, 2000);
  const int tests = int(g.grad.size());
  // Per-block Welch tests of (scale * G-PT gradient + direct differences) vs PT's
  // differences; scale 1 must pass. The splat convention (no x2: both pixels of a pair
  // add their symmetric-MIS-weighted estimates, whose weights sum to one over the four
  // techniques, into one forward-difference buffer normalized by the per-pixel count)
  // is tested by scales 2 and 0.5: either error must be detected.
  auto worst_at = [&](double scale, double* zmax) {
    double worst = 0, z = 0;
    for (int i = 0; i < tests; ++i) {
      worst = std::max(worst, ratio(g.scaled(size_t(i), scale), p.direct[size_t(i)], 1.0, tests, &z));
      if (zmax) *zmax = std::max(*zmax, std::abs(z));
    }
    return worst;
  };
  double zmax = 0;
  const double worst = worst_at(1.0, &zmax), worst_x2 = worst_at(2.0, nullptr), worst_half = worst_at(0.5, nullptr);
  // Negative control: the gradients' total over all blocks (signed by their mean) x 1.1.
  std::vector<double> gsum(kRuns, 0.0), psum(kRuns, 0.0);
  for (int i = 0; i < tests; ++i) {
    const std::vector<double> gi = g.scaled(size_t(i), 1.0);
    const double m = moments(gi).mean;
    if (!(std::abs(m) > 0)) continue;
    for (int r = 0; r < kRuns; ++r) {
      gsum[size_t(r)] += gi[size_t(r)] * (m > 0 ? 1 : -1);
      psum[size_t(r)] += p.direct[size_t(i)][size_t(r)] * (m > 0 ? 1 : -1);
    }
  }
  const double worst_scaled = ratio(gsum, psum, 1.1, 1, nullptr);
  double zl2 = 0;
  const double l2 = ratio(g.mean, p.mean, 1.0, 1, &zl2);
  std::printf("gpt unbiasedness: %d gradient blocks, max |z| %.2f (worst |t|/crit %.2f; x2 splat %.2f, x0.5 splat "
              "%.2f); L2 mean %.5f vs PT %.5f, z %.2f; 1.1x-scaled total |t|/crit %.2f\n",
              tests, zmax, worst, worst_x2, worst_half, moments(g.mean).mean, moments(p.mean).mean, zl2, worst_scaled);
  REQUIRE(worst < 1.0);
  REQUIRE(worst_x2 > 1.0);
  REQUIRE(worst_half > 1.0);
  REQUIRE(l2 < 1.0);
  REQUIRE(worst_scaled > 1.0);
}
