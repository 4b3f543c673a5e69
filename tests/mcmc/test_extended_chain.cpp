// GD-MLT's extended state z = (x, j) (Manzi et al. 2014, Sec. 4) on a known target. The
// "pixel" is a cell of a 3x3 grid over (u1, u2); its neighbour set N has 2, 3 or 4
// members (corner, edge, centre, as pixels of an image); coordinate u0 chooses
// j = floor(u0 |N|) and the chain redraws it uniformly at every step
// (ChainOptions::redraw_first = 1, as `gdmlt`). Target f(cell, j) = w(cell) (1 + j), so in
// primary sample space the state (cell, j) has probability f(cell, j) / |N_cell| / 9 / b.
// A chi-square test of the thinned visit histogram (thinning from the same Doeblin bound
// as test_chain_density.cpp: large steps propose uniformly on the whole cube, so
// delta = p_L b / f_max) must accept this chain and reject a broken neighbour proposal:
// j = floor(4 u0) mod |N| (not uniform when |N| = 3). Watched: p-value < 1e-10 for it.
#include <boost/math/distributions/chi_squared.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "mcmc/chain.h"

using namespace dp;

namespace {
constexpr double kW[3][3] = {{1, 3, 2}, {2, 1, 4}, {3, 2, 1}};

int neighbours(int cx, int cy) { return (cx > 0) + (cx < 2) + (cy > 0) + (cy < 2); }

class ExtendedTarget final : public mcmc::Target {
 public:
  explicit ExtendedTarget(bool modulo_bug) : m_bug(modulo_bug) {}
  mcmc::TargetValue evaluate(pathspace::SampleStream& stream) override {
    const float u0 = stream.next();
    const Vec2 u = stream.next2();
    const int cx = std::min(2, int(u.x() * 3.0f)), cy = std::min(2, int(u.y() * 3.0f));
    const int n = neighbours(cx, cy);
    const int j = m_bug ? int(u0 * 4.0f) % n : std::min(n - 1, int(u0 * float(n)));
    mcmc::TargetValue t;
    t.f = kW[cy][cx] * (1.0 + j);
    t.raster = Vec2(float((cy * 3 + cx) * 4 + j), 0.0f);  // histogram bin
    return t;
  }

 private:
  bool m_bug;
};

double p_value(bool modulo_bug) {
  constexpr int kKept = 40000;
  constexpr double kEta = 1e-4, kPLarge = 0.3;
  std::vector<double> expected(36, 0.0);
  double b = 0, fmax = 0;
  for (int cy = 0; cy < 3; ++cy)
    for (int cx = 0; cx < 3; ++cx) {
      const int n = neighbours(cx, cy);
      for (int j = 0; j < n; ++j) {
        const double f = kW[cy][cx] * (1.0 + j);
        expected[size_t((cy * 3 + cx) * 4 + j)] = f / n / 9.0;
        b += f / n / 9.0;
        fmax = std::max(fmax, f);
      }
    }
  const double delta = kPLarge * b / fmax;
  const int k = int(std::ceil(std::log(kEta / (kKept + 1)) / std::log(1.0 - delta)));
  ExtendedTarget target(modulo_bug);
  mcmc::ChainOptions opt;
  opt.large_step_prob = kPLarge;
  opt.redraw_first = 1;
  mcmc::Chain chain(target, opt, 9, 0);
  chain.start({});
  std::vector<double> count(36, 0.0);
  for (int i = 0; i < k; ++i) chain.step();  // burn-in: one gap
  for (int s = 0; s < kKept; ++s) {
    for (int i = 0; i < k; ++i) chain.step();
    count[size_t(chain.current().raster.x())] += 1;
  }
  double chi2 = 0;
  int bins = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] == 0.0) {
      REQUIRE(count[i] == 0.0);  // a neighbour that does not exist is never visited
      continue;
    }
    const double e = expected[i] / b * kKept;
    chi2 += (count[i] - e) * (count[i] - e) / e;
    ++bins;
  }
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(bins - 1), chi2));
}
}  // namespace

TEST_CASE("mcmc: the extended (x, j) chain with a redrawn neighbour reproduces its target", "[stat]") {
  const double p = p_value(false);
  INFO("p-value " << p);
  REQUIRE(p > 0.01);
  const double wrong = p_value(true);
  INFO("j = floor(4 u0) mod |N|: p-value " << wrong);
  REQUIRE(wrong < 0.01);
}
