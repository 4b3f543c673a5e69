// Unbiasedness of G-PT against the reference PT on a small lit box with a glossy and a
// diffuse sphere: (1) block sums of the dx / dy layers equal block sums of differences of
// PT's pixel expectations, (2) the mean of the L2 reconstruction equals PT's image mean.
// Welch t-tests over independent renders (fixed seeds), Sidak-corrected over blocks;
// thresholds come from the estimators' sample variances. A 10% scaled gradient total and
// a x2 or x0.5 per-pair splat factor must fail.
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/integrator.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
constexpr int kRes = 16, kBlock = 4, kRuns = 10;

const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  return r.layers[0].image;
}

// Per run and block: the sum of forward differences over the block (dx blocks, then dy
// blocks), split for G-PT into its gradient layers' part (`grad`) and its direct layer's
// part (`direct`: emitters seen from the camera are kept out of the gradients; their
// differences are PT's depth-1 term), plus the image mean (L2 for G-PT).
struct Blocks {
  std::vector<std::vector<double>> grad, direct;
  std::vector<double> mean;
  // One run of every block with the gradient part scaled (a x2 / x0.5 splat error).
  std::vector<double> scaled(size_t block, double s) const {
    std::vector<double> v(grad[block].size());
    for (size_t r = 0; r < v.size(); ++r) v[r] = s * grad[block][r] + direct[block][r];
    return v;
  }
};

Blocks stats(const scene::Scene& s, const std::string& integrator, int spp, uint64_t seed0) {
  integrators::Settings settings;
  auto in = integrators::make_integrator(integrator, settings);
  const int nb = kRes / kBlock;
  Blocks out;
  out.grad.resize(size_t(2 * nb * nb));
  out.direct.resize(size_t(2 * nb * nb));
  for (int r = 0; r < kRuns; ++r) {
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed0 + uint64_t(r);
    opt.threads = 2;
    opt.max_depth = 5;
    opt.quiet = true;
    const auto res = in->render(s, opt);
    const bool gpt = integrator == "gpt";
    // PT: differences of the image (all in `direct`); G-PT: its gradient layers plus the
    // differences of its direct layer.
    const core::Image& img = gpt ? layer(res, "direct") : res.layers[0].image;
    auto px = [&](int x, int y) { return double(img(x, y).sum()); };
    for (int by = 0; by < nb; ++by)
      for (int bx = 0; bx < nb; ++bx) {
        double sx = 0, sy = 0, gx = 0, gy = 0;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
            if (x + 1 < kRes) {
              sx += px(x + 1, y) - px(x, y);
              if (gpt) gx += double(layer(res, "dx")(x, y).sum());
            }
            if (y + 1 < kRes) {
              sy += px(x, y + 1) - px(x, y);
              if (gpt) gy += double(layer(res, "dy")(x, y).sum());
            }
          }
        out.direct[size_t(by * nb + bx)].push_back(sx);
        out.direct[size_t(nb * nb + by * nb + bx)].push_back(sy);
        out.grad[size_t(by * nb + bx)].push_back(gx);
        out.grad[size_t(nb * nb + by * nb + bx)].push_back(gy);
      }
    out.mean.push_back((gpt ? layer(res, "recon_l2") : res.layers[0].image).mean().sum());
  }
  return out;
}

struct Moments {
  double mean, var;
};
Moments moments(const std::vector<double>& v) {
  double m = 0, s2 = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  for (double x : v) s2 += (x - m) * (x - m);
  return {m, s2 / double(v.size() - 1)};
}
// |t| / critical (Welch, Sidak over `tests`); < 1 passes.
double ratio(const std::vector<double>& a, const std::vector<double>& b, double scale_a, int tests, double* z) {
  Moments ma = moments(a), mb = moments(b);
  ma.mean *= scale_a;
  ma.var *= scale_a * scale_a;
  const double va = ma.var / double(a.size()), vb = mb.var / double(b.size());
  if (va + vb <= 0) return 0;
  const double t = (ma.mean - mb.mean) / std::sqrt(va + vb);
  const double dof = (va + vb) * (va + vb) / (va * va / double(a.size() - 1) + vb * vb / double(b.size() - 1));
  const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(tests));
  const double crit = boost::math::quantile(boost::math::complement(boost::math::students_t(dof), alpha / 2));
  if (z) *z = t;
  return std::abs(t) / crit;
}
}  // namespace

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
