// The chi-square harness itself: accepts correct sampler/pdf pairs and rejects wrong
// ones (so BSDF and emitter tests built on it can fail).
#include <catch2/catch.hpp>

#include "core/warp.h"
#include "tests/support/chi2.h"

using namespace dp;

TEST_CASE("chi-square accepts warps with their pdfs", "[stat]") {
  test::Chi2Options opt;
  opt.test_count = 3;
  auto r1 = test::chi2_sphere([](core::Rng& r) { return std::optional<Vec3>(core::warp::square_to_cosine_hemisphere(r.uniform2())); },
                              [](const Vec3& w) { return double(core::warp::square_to_cosine_hemisphere_pdf(w)); }, opt);
  INFO(r1.report);
  CHECK(r1.passed);
  auto r2 = test::chi2_sphere([](core::Rng& r) { return std::optional<Vec3>(core::warp::square_to_uniform_sphere(r.uniform2())); },
                              [](const Vec3&) { return double(core::warp::square_to_uniform_sphere_pdf()); }, opt);
  INFO(r2.report);
  CHECK(r2.passed);
  // Half of the samples absorbed: pdf integrates to 0.5.
  auto r3 = test::chi2_sphere(
      [](core::Rng& g) -> std::optional<Vec3> {
        if (g.uniform() < 0.5f) return std::nullopt;
        return core::warp::square_to_uniform_cone(g.uniform2(), 0.8f);
      },
      [](const Vec3& w) { return 0.5 * double(core::warp::square_to_uniform_cone_pdf(w, 0.8f)); }, opt);
  INFO(r3.report);
  CHECK(r3.passed);
}

TEST_CASE("chi-square rejects a wrong pdf", "[stat]") {
  // Cosine-distributed samples tested against the uniform-hemisphere pdf.
  auto r = test::chi2_sphere([](core::Rng& g) { return std::optional<Vec3>(core::warp::square_to_cosine_hemisphere(g.uniform2())); },
                             [](const Vec3& w) { return double(core::warp::square_to_uniform_hemisphere_pdf(w)); });
  CHECK_FALSE(r.passed);
  // A subtly wrong pdf (cos^1.1 instead of cos) is caught too.
  auto r2 = test::chi2_sphere(
      [](core::Rng& g) { return std::optional<Vec3>(core::warp::square_to_cosine_hemisphere(g.uniform2())); },
      [](const Vec3& w) { return w.z() > 0 ? std::pow(double(w.z()), 1.1) * 2.1 / (2 * kPiD) : 0.0; });
  CHECK_FALSE(r2.passed);
}
