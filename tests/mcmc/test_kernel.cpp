// The Kelemen small-step kernel: its offset d has the even density
// p(d) = 1 / (2 |d| log(s2 / s1)) on s1 <= |d| <= s2 (chi-square over log|d| x sign
// cells), and a step is the torus translation y = wrap(x + d) staying in [0, 1) even
// from the ends of the interval. An even offset density and a translation make
// K(x -> y) = K(y -> x). A kernel with a biased sign must fail the same chi-square.
#include <boost/math/distributions/chi_squared.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "mcmc/chain.h"

using namespace dp;

namespace {
constexpr int kLogBins = 10, kSamples = 200000;

// p-value of the offsets drawn by `offset` against the analytic density.
template <typename F>
double offset_p_value(const mcmc::KelemenKernel& k, F&& offset) {
  std::vector<double> count(2 * kLogBins, 0.0);
  const double lo = std::log(k.s1), span = std::log(k.s2 / k.s1);
  for (int i = 0; i < kSamples; ++i) {
    const double d = offset();
    const double t = (std::log(std::abs(d)) - lo) / span;  // uniform on [0, 1] under the claim
    REQUIRE(t >= -1e-12);
    REQUIRE(t <= 1 + 1e-12);
    const int bin = std::min(kLogBins - 1, int(t * kLogBins));
    count[size_t(bin + (d > 0 ? kLogBins : 0))] += 1;
  }
  const double expected = double(kSamples) / (2 * kLogBins);  // every cell has mass 1/20
  double chi2 = 0;
  for (double c : count) chi2 += (c - expected) * (c - expected) / expected;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(2 * kLogBins - 1), chi2));
}
}  // namespace

TEST_CASE("mcmc: the small-step offset has Kelemen's even density", "[unit]") {
  const mcmc::KelemenKernel k;
  core::Rng rng(11, 2);
  const double p = offset_p_value(k, [&] { return k.offset(rng); });
  INFO("p-value " << p);
  REQUIRE(p > 0.01);
  // A kernel that moves right 55% of the time (not symmetric) is rejected.
  core::Rng rng2(11, 3);
  const double p_wrong = offset_p_value(k, [&] {
    const double d = std::abs(k.offset(rng2));
    return rng2.uniform() < 0.55f ? d : -d;
  });
  INFO("p-value of the asymmetric kernel " << p_wrong);
  REQUIRE(p_wrong < 0.01);
}

TEST_CASE("mcmc: a small step is a torus translation and stays in [0, 1)", "[unit]") {
  const mcmc::KelemenKernel k;
  const float starts[] = {0.0f, 1e-7f, 0.0005f, 0.5f, 0.9995f, 1.0f - 0x1p-24f};
  for (float x0 : starts) {
    core::Rng a(5, 1), b(5, 1);  // the same stream: perturb() draws what offset() draws
    for (int i = 0; i < 20000; ++i) {
      const double d = k.offset(a);
      const float y = k.perturb(x0, b);
      REQUIRE(y >= 0.0f);
      REQUIRE(y < 1.0f);
      double diff = double(y) - double(x0);  // circular difference in [-0.5, 0.5)
      diff -= std::floor(diff + 0.5);
      REQUIRE(std::abs(diff - d) < 1e-6);
    }
  }
  // Long random walks from the ends never leave [0, 1).
  core::Rng rng(9, 9);
  std::vector<float> u = {0.0f, 1.0f - 0x1p-24f, 0.999999f, 1e-9f};
  for (int i = 0; i < 100000; ++i) {
    k.perturb_all(u, rng);
    for (float x : u) REQUIRE((x >= 0.0f && x < 1.0f));
  }
  REQUIRE(mcmc::wrap_unit(1.0 - 1e-9) == 0.0f);
  REQUIRE(mcmc::wrap_unit(-1e-3) == Approx(0.999f));
}

TEST_CASE("mcmc: the acceptance rule rejects zero and non-finite proposals", "[unit]") {
  REQUIRE(mcmc::metropolis_acceptance(2.0, 1.0) == 0.5);
  REQUIRE(mcmc::metropolis_acceptance(1.0, 3.0) == 1.0);
  REQUIRE(mcmc::metropolis_acceptance(1.0, 0.0) == 0.0);
  REQUIRE(mcmc::metropolis_acceptance(1.0, std::nan("")) == 0.0);
  REQUIRE(mcmc::metropolis_acceptance(1.0, INFINITY) == 0.0);
  REQUIRE(mcmc::metropolis_acceptance(0.0, 1.0) == 1.0);
}
