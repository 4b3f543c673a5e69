// Unbiasedness of the L2 reconstruction (Lehtinen et al. 2013, Sec. 4: the L2 solution
// is linear in (I_g, b), so unbiased inputs give an unbiased image).
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>

#include "helpers.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

struct ZTest {
  double max_abs_t = 0.0;
  double threshold = 0.0;
};

// Per-pixel, per-channel t-test of mean(reconstruction) == truth over `runs` independent
// noisy inputs; Sidak-corrected so that the whole image is tested at family-wise level
// `fwer`. `gradient_scale` != 1 makes the estimator biased (negative control).
ZTest run_ztest(const Kernel& k, L2Method method, int runs, float gradient_scale, uint64_t seed) {
  const core::Image truth = test_image(k.width(), k.height());
  const std::vector<Rgb> exact_b = apply_kernel(k, truth);
  const size_t n = truth.size();
  std::vector<double> sum(3 * n, 0.0), sum2(3 * n, 0.0);
  SolveOptions opt;
  opt.method = method;
  opt.threads = 2;
  for (int run = 0; run < runs; ++run) {
    core::Rng rng(seed, uint64_t(run));
    Problem p;
    p.kernel = k;
    p.primal = truth;
    // Heavy primal noise, light gradient noise: the regime gradient-domain rendering is for.
    for (auto& v : p.primal.pixels())
      for (int c = 0; c < 3; ++c) v[c] += float(0.5 * gaussian(rng));
    p.b = exact_b;
    for (auto& v : p.b) {
      v *= gradient_scale;
      for (int c = 0; c < 3; ++c) v[c] += float(0.05 * gaussian(rng));
    }
    const core::Image x = solve_l2(p, opt).image;
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const double e = double(x[i][c]) - double(truth[i][c]);
        sum[3 * i + size_t(c)] += e;
        sum2[3 * i + size_t(c)] += e * e;
      }
  }
  ZTest z;
  const double m = double(runs);
  for (size_t k3 = 0; k3 < 3 * n; ++k3) {
    const double mean = sum[k3] / m;
    const double var = (sum2[k3] - m * mean * mean) / (m - 1.0);
    z.max_abs_t = std::max(z.max_abs_t, std::abs(mean) / std::sqrt(var / m));
  }
  const double fwer = 1e-3, tests = double(3 * n);
  const double per_test = -std::expm1(std::log1p(-fwer) / tests);  // Sidak
  z.threshold = boost::math::quantile(boost::math::complement(boost::math::students_t(m - 1.0), per_test / 2.0));
  return z;
}

}  // namespace

TEST_CASE("L2 reconstruction is unbiased (DCT, grid)", "[stat]") {
  const Kernel k = Kernel::forward_differences(32, 24);
  const ZTest z = run_ztest(k, L2Method::direct, 400, 1.0f, 1234);
  INFO("max |t| " << z.max_abs_t << ", threshold " << z.threshold);
  CHECK(z.max_abs_t < z.threshold);
  // Negative control: 10% too small gradients are a bias this test must detect.
  const ZTest biased = run_ztest(k, L2Method::direct, 400, 0.9f, 1234);
  INFO("biased: max |t| " << biased.max_abs_t);
  CHECK(biased.max_abs_t > biased.threshold);
}

TEST_CASE("L2 reconstruction is unbiased (PCG, adaptive kernel)", "[stat]") {
  core::Rng rng(99, 0);
  const Kernel k = random_kernel(24, 18, 4, rng);
  const ZTest z = run_ztest(k, L2Method::cg, 300, 1.0f, 4321);
  INFO("max |t| " << z.max_abs_t << ", threshold " << z.threshold);
  CHECK(z.max_abs_t < z.threshold);
  const ZTest biased = run_ztest(k, L2Method::cg, 300, 0.9f, 4321);
  INFO("biased: max |t| " << biased.max_abs_t);
  CHECK(biased.max_abs_t > biased.threshold);
}
