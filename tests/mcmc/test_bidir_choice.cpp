// The discrete part of the bidirectional mutation (mcmc/bidir_choice.h) and its
// two-tailed geometric lengths (mcmc/two_tailed_geometric.h):
//  * the distribution's pmf sums to 1, has the ratios base^(|j-c| - |i-c|), and its
//    inverse-CDF sampler on a uniform grid of N points hits each value within 1/N of it;
//  * on random path shapes (lengths, degenerate vertices, hittable endpoints), the choice
//    frequencies of sample_bidir_choice match bidir_choice_pmf (chi-square over every
//    (k', l, m, s) plus a failure cell whose mass is 1 - sum of the enumerated pmf);
//  * every sampled choice has a reverse that the pmf allows on the proposal's shape.
#include <boost/math/distributions/chi_squared.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "core/rng.h"
#include "mcmc/bidir_choice.h"
#include "mcmc/two_tailed_geometric.h"

using namespace dp;
using namespace dp::mcmc;

TEST_CASE("two-tailed geometric: normalised, geometric ratios, exact inverse CDF", "[unit]") {
  for (const auto& [centre, lo, hi] : {std::tuple{2, 1, 9}, std::tuple{5, 3, 12}, std::tuple{7, 3, 5}, std::tuple{4, 4, 4}}) {
    const TwoTailedGeometric d(2.0, centre, lo, hi);
    double sum = 0;
    for (int i = lo; i <= hi; ++i) {
      sum += d.pmf(i);
      for (int j = lo; j <= hi; ++j)
        CHECK(d.pmf(i) / d.pmf(j) == Approx(std::pow(2.0, std::abs(j - centre) - std::abs(i - centre))).epsilon(1e-12));
    }
    CHECK(sum == Approx(1.0).epsilon(1e-12));
    CHECK(d.pmf(lo - 1) == 0.0);
    CHECK(d.pmf(hi + 1) == 0.0);
    const int n = 1 << 16;
    std::map<int, int> count;
    for (int i = 0; i < n; ++i) ++count[d.sample((double(i) + 0.5) / n)];
    for (int i = lo; i <= hi; ++i) CHECK(std::abs(double(count[i]) / n - d.pmf(i)) <= 1.0 / n);
  }
  CHECK(TwoTailedGeometric(2.0, 3, 5, 4).empty());
}

namespace {

using Key = std::tuple<int, int, int, int>;  // k', l, m, s

// A random shape: extended length k in [3, 8], interior vertices degenerate with
// probability 0.3, the supernodes as a pinhole scene (camera supernode degenerate).
BidirShape random_shape(core::Rng& rng) {
  BidirShape s;
  s.k = 3 + int(rng.uniform() * 6.0f);
  s.degenerate.assign(size_t(s.k + 1), 0);
  for (int e = 1; e < s.k; ++e) s.degenerate[size_t(e)] = rng.uniform() < 0.3f;
  s.degenerate[size_t(s.k)] = 1;
  s.degenerate[0] = rng.uniform() < 0.2f;
  s.light_hittable = rng.uniform() < 0.7f;
  return s;
}

// Every choice the pmf gives mass to, with that mass (per split).
std::map<Key, double> enumerate(const BidirShape& shape, const BidirLengths& lengths) {
  std::map<Key, double> out;
  for (int l = 0; l <= shape.k; ++l)
    for (int m = l + 1; m <= shape.k; ++m)
      for (int ka = 1; ka <= lengths.k_max; ++ka) {
        BidirChoice c{l, m, ka, 0};
        const double p = bidir_choice_pmf(shape, lengths, c);
        if (!(p > 0)) continue;
        int s_min = 0, s_max = 0;
        bidir_split_range(shape, c, s_min, s_max);
        for (int s = s_min; s <= s_max; ++s) out[Key{c.new_length(shape.k), l, m, s}] = p;
      }
  return out;
}

}  // namespace

TEST_CASE("bidirectional mutation: sampled choices follow their pmf; every reverse is possible", "[stat]") {
  core::Rng rng(17, 3);
  const BidirLengths lengths{3, 9};
  const int shapes = 40, draws = 40000;
  int tested = 0, reverses = 0, reverse_missing = 0, impossible = 0;
  double worst_p = 1.0;
  for (int i = 0; i < shapes; ++i) {
    const BidirShape shape = random_shape(rng);
    const std::map<Key, double> pmf = enumerate(shape, lengths);
    double mass = 0;
    for (const auto& [key, p] : pmf) mass += p;
    REQUIRE(mass <= 1.0 + 1e-12);
    std::map<Key, int> count;
    int failed = 0;
    core::Rng draw_rng(29, uint64_t(i));
    pathspace::IndependentStream stream(draw_rng);
    for (int d = 0; d < draws; ++d) {
      BidirChoice c;
      if (!sample_bidir_choice(shape, lengths, stream, c)) {
        ++failed;
        continue;
      }
      const Key key{c.new_length(shape.k), c.l, c.m, c.s};
      if (!pmf.count(key)) {  // a choice of pmf 0
        ++impossible;
        continue;
      }
      ++count[key];
      // The proposal: the source's vertices 0..l and m..k around ka - 1 new (regular) ones.
      BidirShape y;
      y.k = c.new_length(shape.k);
      y.light_hittable = shape.light_hittable;
      y.camera_hittable = shape.camera_hittable;
      for (int e = 0; e <= c.l; ++e) y.degenerate.push_back(shape.degenerate[size_t(e)]);
      for (int e = 1; e < c.ka; ++e) y.degenerate.push_back(0);
      for (int e = c.m; e <= shape.k; ++e) y.degenerate.push_back(shape.degenerate[size_t(e)]);
      if (y.k >= lengths.k_min && y.k <= lengths.k_max) {
        reverse_missing += !(bidir_choice_pmf(y, lengths, c.reverse()) > 0.0);
        ++reverses;
      }
    }
    // Chi-square over the choices (cells with expectation >= 5 kept, the rest pooled
    // with the failure cell).
    double chi2 = 0, pooled_expected = draws * (1.0 - mass), pooled_observed = failed;
    int cells = 0;
    for (const auto& [key, p] : pmf) {
      const double e = draws * p;
      const double o = count.count(key) ? count.at(key) : 0;
      if (e < 5) {
        pooled_expected += e;
        pooled_observed += o;
        continue;
      }
      chi2 += (o - e) * (o - e) / e;
      ++cells;
    }
    if (pooled_expected >= 5) {
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
      ++cells;
    } else {
      CHECK(pooled_observed <= pooled_expected + 5 * std::sqrt(pooled_expected + 1));
    }
    if (cells < 2) continue;
    const double p = boost::math::cdf(boost::math::complement(boost::math::chi_squared(cells - 1), chi2));
    worst_p = std::min(worst_p, p);
    ++tested;
  }
  // 40 independent tests at a Sidak-corrected 1% level.
  const double alpha = 1.0 - std::pow(0.99, 1.0 / shapes);
  std::printf("bidir choice: %d shapes tested, %d reverses checked, smallest chi-square p %.3g (threshold %.3g)\n",
              tested, reverses, worst_p, alpha);
  CHECK(tested > 30);
  CHECK(reverses > 100000);
  CHECK(reverse_missing == 0);
  CHECK(impossible == 0);
  CHECK(worst_p > alpha);
}
