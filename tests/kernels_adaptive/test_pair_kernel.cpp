// The pair kernel's rows and N_i (Manzi et al. 2014, Sec. 3.5 symmetric / non-symmetric
// rules, Sec. 4 N_i, Algorithm 1), checked against an independent reading of the paper.
#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <set>
#include <utility>

#include "core/error.h"
#include "helpers.h"
#include "kernels_adaptive/kernel_problem.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::kernels_adaptive;
using Pair = std::pair<int32_t, int32_t>;

namespace {

// P recomputed from Eq. 7 directly: each pixel's n best window pixels by
// (cost, squared distance, index).
std::set<Pair> reference_pairs(const Features& f, const AffinityParams& p) {
  std::set<Pair> P;
  const int w = f.width, h = f.height, r = p.window / 2;
  for (int yi = 0; yi < h; ++yi)
    for (int xi = 0; xi < w; ++xi) {
      const int i = yi * w + xi;
      std::vector<std::tuple<double, int, int>> c;
      for (int y = yi - r; y <= yi + r; ++y)
        for (int x = xi - r; x <= xi + r; ++x) {
          if (x < 0 || y < 0 || x >= w || y >= h || (x == xi && y == yi)) continue;
          const int j = y * w + x;
          const double dn = (f.normal[size_t(i)] - f.normal[size_t(j)]).cast<double>().squaredNorm();
          const double da = (f.albedo[size_t(i)] - f.albedo[size_t(j)]).cast<double>().matrix().squaredNorm();
          const double dd = double(f.depth[size_t(i)]) - double(f.depth[size_t(j)]);
          const auto e = [](double d2, float tau, float sigma) {
            return std::max(0.0, d2 - double(tau)) / (double(sigma) * double(sigma));
          };
          const double cost = std::max({e(dn, p.tau_normal, p.sigma_normal), e(da, p.tau_texture, p.sigma_texture),
                                        e(dd * dd, p.tau_depth, p.sigma_depth)});
          c.emplace_back(cost, (x - xi) * (x - xi) + (y - yi) * (y - yi), j);
        }
      std::sort(c.begin(), c.end());
      for (size_t k = 0; k < std::min(c.size(), size_t(p.neighbours)); ++k) P.insert({i, std::get<2>(c[k])});
    }
  return P;
}

// Every rule of the contract in pair_kernel.h, given the pair set P it must encode.
void check_rules(const PairKernel& k, const std::set<Pair>& P, int window) {
  const int32_t n = int32_t(k.width * k.height);
  REQUIRE(k.offsets.size() == size_t(n) + 1);
  REQUIRE(k.offsets.front() == 0);
  REQUIRE(size_t(k.offsets.back()) == k.entries.size());
  CHECK(k.rows.size() == P.size());  // one row per ij in P
  // Every ij in P has its row {a = j, b = i}; rows are exactly those.
  std::map<Pair, int32_t> row_of;  // (a, b) -> row
  for (int32_t r = 0; r < int32_t(k.rows.size()); ++r) {
    const auto [a, b] = std::pair(k.rows[size_t(r)].i, k.rows[size_t(r)].j);
    REQUIRE(a >= 0);
    REQUIRE(b >= 0);
    REQUIRE(a < n);
    REQUIRE(b < n);
    CHECK(std::abs(a % k.width - b % k.width) <= window / 2);
    CHECK(std::abs(a / k.width - b / k.width) <= window / 2);
    CHECK(row_of.emplace(Pair{a, b}, r).second);  // no duplicate rows
    CHECK(P.count({b, a}) == 1);
  }
  std::vector<int> writers(k.rows.size(), 0);
  for (int32_t i = 0; i < n; ++i) {
    std::set<int32_t> expected;  // N_i = {j : ij in P or ji in P}
    for (const auto& [a, b] : P) {
      if (a == i) expected.insert(b);
      if (b == i) expected.insert(a);
    }
    const auto N = neighbours(k, i);
    std::vector<int32_t> got;
    for (const auto& e : N) got.push_back(e.j);
    CHECK(std::is_sorted(got.begin(), got.end()));
    CHECK(std::set<int32_t>(got.begin(), got.end()) == expected);
    CHECK(got.size() == expected.size());
    for (const auto& e : N) {
      const bool ij = P.count({i, e.j}) != 0, ji = P.count({e.j, i}) != 0;
      REQUIRE(e.row >= 0);
      REQUIRE(size_t(e.row) < k.rows.size());
      const auto& row = k.rows[size_t(e.row)];
      ++writers[size_t(e.row)];
      INFO("pixel " << i << " -> " << e.j << " row " << e.row << " weight " << e.weight);
      if (ij && ji) {  // symmetric: own row I_i - I_j = 2 Delta^i_ij
        CHECK(e.weight == 2.0f);
        CHECK((row.i == e.j && row.j == i));
      } else if (ij) {  // I_i - I_j = Delta_ij, pixel i's part enters with +
        CHECK(e.weight == 1.0f);
        CHECK((row.i == e.j && row.j == i));
      } else {  // ji only: I_j - I_i = Delta_ji, pixel i's part enters with -
        CHECK(e.weight == -1.0f);
        CHECK((row.i == i && row.j == e.j));
      }
    }
  }
  // A symmetric pair's rows have one writer each, a non-symmetric pair's row two.
  for (size_t r = 0; r < k.rows.size(); ++r) {
    const bool symmetric = P.count({k.rows[r].i, k.rows[r].j}) && P.count({k.rows[r].j, k.rows[r].i});
    CHECK(writers[r] == (symmetric ? 1 : 2));
  }
}

}  // namespace

TEST_CASE("adaptive kernel: P from Eq. 7, rows and N_i follow Sec. 3.5 / Algorithm 1", "[unit]") {
  for (uint64_t seed = 0; seed < 4; ++seed) {
    core::Rng rng(seed, 3);
    const int w = 9 + int(seed), h = 7 + int(seed % 2);
    const Features f = test::synthetic_features(w, h, 2 + int(seed % 2), rng);
    AffinityParams p;
    if (seed == 3) p.neighbours = 6;
    const PairKernel k = adaptive_kernel(f, p);
    const std::set<Pair> P = reference_pairs(f, p);
    INFO("seed " << seed);
    // Each pixel chose exactly n partners (the window always has more than n here).
    std::vector<int> chosen(size_t(w * h), 0);
    for (const auto& [i, j] : P) ++chosen[size_t(i)];
    CHECK(*std::min_element(chosen.begin(), chosen.end()) == p.neighbours);
    CHECK(*std::max_element(chosen.begin(), chosen.end()) == p.neighbours);
    check_rules(k, P, p.window);
    // Both kinds of pair occur, so both rules were exercised.
    size_t symmetric = 0;
    for (const auto& [i, j] : P) symmetric += P.count({j, i});
    CHECK(symmetric > 0);
    CHECK(symmetric < P.size());
  }
}

TEST_CASE("adaptive kernel: exact splats reconstruct the image exactly (L2)", "[unit]") {
  core::Rng rng(11, 4);
  const int w = 12, h = 9;
  const PairKernel k = adaptive_kernel(test::synthetic_features(w, h, 3, rng));
  core::Image img(w, h);
  for (auto& c : img.pixels()) c = Rgb(rng.uniform(), rng.uniform(), 2.0f * rng.uniform());
  const std::vector<Rgb> b = test::exact_splats(k, img.pixels(), 5);
  // Non-symmetric rows hold I_b - I_a exactly; a symmetric pair's two rows average to it.
  for (size_t r = 0; r < k.rows.size(); ++r) {
    const auto [a, bb] = std::pair(size_t(k.rows[r].i), size_t(k.rows[r].j));
    const auto rev = std::find_if(k.rows.begin(), k.rows.end(), [&](const reconstruct::PixelPair& q) {
      return size_t(q.i) == bb && size_t(q.j) == a;
    });
    const Rgb truth = img[bb] - img[a];
    const Rgb got = rev == k.rows.end() ? b[r] : Rgb(0.5f * (b[r] - b[size_t(rev - k.rows.begin())]));
    CHECK((got - truth).abs().maxCoeff() < 1e-5f);
  }
  // With the true image as primal the true image solves the normal equations
  // H^T H I = H^T b, so the solver returns it (to its CG tolerance).
  reconstruct::Problem prob = make_problem(k, img, b, 0.2f);
  CHECK_FALSE(prob.kernel.is_forward_difference_grid());
  const core::Image out = reconstruct::solve_l2(prob).image;
  for (size_t i = 0; i < img.size(); ++i) CHECK((out[i] - img[i]).abs().maxCoeff() < 1e-4f);
}

TEST_CASE("two-region features: no pair crosses the edge", "[unit]") {
  const int w = 14, h = 8;
  Features f;
  f.width = w;
  f.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f.normal.push_back(x < w / 2 ? Vec3(1.0f, 0.5f, 0.5f) : Vec3(0.5f, 1.0f, 0.5f));  // normal A | normal B
      f.albedo.push_back(Rgb(0.5f, 0.5f, 0.5f));
      f.depth.push_back(0.5f);
    }
  const PairKernel k = adaptive_kernel(f, {});
  CHECK(k.rows.size() == size_t(4 * w * h));
  for (const auto& row : k.rows) {
    INFO("row " << row.i << " -> " << row.j);
    CHECK((row.i % w < w / 2) == (row.j % w < w / 2));
  }
  for (int32_t i = 0; i < w * h; ++i)
    for (const auto& e : neighbours(k, i)) CHECK((i % w < w / 2) == (e.j % w < w / 2));
}

TEST_CASE("standard kernel: forward-difference rows, 4-neighbour N_i", "[unit]") {
  for (const auto& [w, h] : {Pair{6, 4}, Pair{1, 5}, Pair{7, 1}, Pair{1, 1}}) {
    const PairKernel k = standard_kernel(w, h);
    const reconstruct::Kernel ref = reconstruct::Kernel::forward_differences(w, h);
    INFO(w << "x" << h);
    REQUIRE(k.rows.size() == ref.rows());
    for (size_t r = 0; r < k.rows.size(); ++r) {
      CHECK(k.rows[r].i == ref.pairs()[r].i);
      CHECK(k.rows[r].j == ref.pairs()[r].j);
    }
    // Standard GDMLT: each forward difference is one non-symmetric row written by both
    // pixels; N_i = the in-image 4-neighbours.
    std::set<Pair> P;
    for (const auto& row : k.rows) P.insert({row.j, row.i});
    check_rules(k, P, 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        CHECK(neighbours(k, y * w + x).size() == size_t((x > 0) + (x + 1 < w) + (y > 0) + (y + 1 < h)));
    const reconstruct::Problem prob = make_problem(k, core::Image(w, h), std::vector<Rgb>(k.rows.size(), Rgb::Zero()));
    CHECK(prob.kernel.is_forward_difference_grid());  // DCT path available
  }
  CHECK_THROWS_AS(standard_kernel(0, 3), ValueError);
}

TEST_CASE("make_problem rejects mismatched sizes", "[unit]") {
  const PairKernel k = standard_kernel(4, 3);
  CHECK_THROWS_AS(make_problem(k, core::Image(3, 3), std::vector<Rgb>(k.rows.size())), ValueError);
  CHECK_THROWS_AS(make_problem(k, core::Image(4, 3), std::vector<Rgb>(k.rows.size() + 1)), ValueError);
  CHECK_THROWS_AS(make_problem(k, core::Image(4, 3), std::vector<Rgb>(k.rows.size()), 0.0f), ValueError);
}
