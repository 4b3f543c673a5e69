// PSSMLT (`--integrator mlt`) against the reference path tracer on a small lit box with
// a glossy sphere. K independent MLT renders (fixed seeds) and K independent PT renders:
// their run-to-run spread gives the standard error of each (MLT's includes the bootstrap
// estimate of b, startup and correlation between mutations -- runs are independent, so
// the sample variance over runs is unbiased whatever the chain's autocorrelation).
// Welch t-tests: the image mean (alpha = 1%) and every 8x8 block (Sidak-corrected to a
// 1% family-wise level). The same tests must reject MLT run with a real defect: an
// asymmetric small step (step length growing with the coordinate) without its Q ratio.
// Also: a render is deterministic for a fixed seed and thread count.
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "integrators/integrator.h"
#include "integrators/mlt/mlt_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;
using test::Moments;
using test::moments;
using test::welch_ratio;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 10;

// Deliberately asymmetric small step (as in test_chain_density.cpp): K(x -> y) != K(y -> x)
// and the chain does not correct for it.
void position_scaled_step(const mcmc::KelemenKernel& kernel, std::vector<float>& u, core::Rng& rng) {
  for (float& x : u) x = mcmc::wrap_unit(double(x) + kernel.offset(rng) * (0.2 + 4.0 * double(x)));
}

// name "mlt-asymmetric": mlt with position_scaled_step.
integrators::RenderResult render(const scene::Scene& s, const std::string& name, int spp, uint64_t seed) {
  integrators::Settings settings;
  std::unique_ptr<integrators::Integrator> in;
  if (name == "mlt-asymmetric") {
    integrators::MltSettings m = integrators::MltSettings::read(settings);
    m.small_step = position_scaled_step;
    in = std::make_unique<integrators::MltIntegrator>(m, settings.to_json());
  } else {
    in = integrators::make_integrator(name, settings);
  }
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = 6;
  opt.quiet = true;
  return in->render(s, opt);
}

// Per run: image mean (channel sum) followed by the block means.
std::vector<std::vector<double>> run_stats(const scene::Scene& s, const std::string& name, int spp, uint64_t seed0,
                                           double* acceptance = nullptr) {
  const int nb = kRes / kBlock;
  std::vector<std::vector<double>> out(size_t(1 + nb * nb));
  for (int r = 0; r < kRuns; ++r) {
    const auto res = render(s, name, spp, seed0 + uint64_t(r));
    if (acceptance) {
      const auto& st = res.stats;
      *acceptance = double(st.get("mlt.accepted_large") + st.get("mlt.accepted_small")) /
                    double(st.get("mlt.large_steps") + st.get("mlt.small_steps"));
    }
    const core::Image& img = res.layers[0].image;
    double all = 0;
    for (int by = 0; by < nb; ++by)
      for (int bx = 0; bx < nb; ++bx) {
        double sum = 0;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) sum += double(img(x, y).sum());
        out[size_t(1 + by * nb + bx)].push_back(sum / (kBlock * kBlock));
        all += sum;
      }
    out[0].push_back(all / (kRes * kRes));
  }
  return out;
}

// Largest ratio over the image-mean test (alpha = 1%) and the block tests (Sidak, 1% family).
double worst_ratio(const std::vector<std::vector<double>>& mlt, const std::vector<std::vector<double>>& pt,
                   double scale, double* mean_ratio) {
  *mean_ratio = welch_ratio(moments(mlt[0], scale), moments(pt[0], 1.0), 0.01);
  const size_t blocks = mlt.size() - 1;
  const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(blocks));
  double worst = *mean_ratio;
  for (size_t i = 1; i < mlt.size(); ++i)
    worst = std::max(worst, welch_ratio(moments(mlt[i], scale), moments(pt[i], 1.0), alpha));
  return worst;
}

std::unique_ptr<scene::Scene> glossy_box(int res) {
  return test::lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                   scene::ConductorFresnel{},
                                                                   scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                       nullptr, res);
}
}  // namespace

TEST_CASE("mlt: PSSMLT agrees with the path tracer (image mean and 8x8 blocks)", "[stat]") {
  const auto s = glossy_box(kRes);
  double acceptance = 0;
  const auto mlt = run_stats(*s, "mlt", 256, 1000, &acceptance);
  const auto pt = run_stats(*s, "path", 64, 2000);
  double mean_ratio = 0;
  const double r = worst_ratio(mlt, pt, 1.0, &mean_ratio);
  const Moments m = moments(mlt[0], 1.0), p = moments(pt[0], 1.0);
  INFO("image mean: MLT " << m.mean << " +- " << std::sqrt(m.var / kRuns) << ", PT " << p.mean << " +- "
                          << std::sqrt(p.var / kRuns) << "; mean |t|/crit " << mean_ratio
                          << ", worst over blocks " << r << "; acceptance " << acceptance);
  REQUIRE(acceptance > 0.0);
  REQUIRE(r < 1.0);
  // The same tests reject MLT with an asymmetric small step and no Q ratio (so they can
  // fail). The image mean cannot see it (b normalises the total: watched |t|/crit 0.67);
  // the blocks do (watched worst |t|/crit 5.4). Power: the image mean's standard error
  // is ~0.17% (MLT) / 0.12% (PT); a block has 1/16 of the pixels, so ~4x that, and the
  // Sidak critical t is ~4.3: a block brighter or darker by more than ~3-4% is detected.
  const auto broken = run_stats(*s, "mlt-asymmetric", 256, 1000);
  double broken_mean_ratio = 0;
  const double r_wrong = worst_ratio(broken, pt, 1.0, &broken_mean_ratio);
  INFO("asymmetric step: mean |t|/crit " << broken_mean_ratio << ", worst " << r_wrong);
  REQUIRE(r_wrong > 1.0);
}

TEST_CASE("mlt: a render is deterministic for a fixed seed and thread count", "[unit]") {
  const auto s = glossy_box(16);
  const auto a = render(*s, "mlt", 8, 7), b = render(*s, "mlt", 8, 7), c = render(*s, "mlt", 8, 8);
  const core::Image &ia = a.layers[0].image, &ib = b.layers[0].image, &ic = c.layers[0].image;
  bool same = true, differs = false;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      same &= (ia(x, y) == ib(x, y)).all();
      differs |= !(ia(x, y) == ic(x, y)).all();
    }
  REQUIRE(same);
  REQUIRE(differs);  // another seed gives another image (the comparison can fail)
  REQUIRE(a.stats.get("mlt.mutations") == 8 * 16 * 16);
  REQUIRE(a.stats.get("mlt.nan_dropped") == 0);
}

// Normalisation that converges: b = mean f over the bootstrap and every large-step
// proposal (all independent uniform primary samples), so Var(b) = sigma_f^2 / n with n =
// bootstrap + large steps. Over R independent runs at two budgets the ratio of b's sample
// variances must be consistent with n_2 / n_1 (two-sided F test, 1%) and significantly
// above 1 (one-sided F test, 1%): b's error falls as 1 / sqrt(render length). With
// large_step_b = false, b rests on the bootstrap alone and its variance does not fall: the
// second test rejects that variant (watched: variance ratio ~1).
namespace {
struct BStats {
  double var = 0;
  double n = 0;  // bootstrap samples + large steps (mean over runs)
};
BStats b_spread(const scene::Scene& s, int spp, bool large_step_b) {
  constexpr int kR = 40;
  std::vector<double> b;
  double n = 0;
  for (int r = 0; r < kR; ++r) {
    integrators::Settings settings;
    settings.set("bootstrap", "200");
    settings.set("large_step_b", large_step_b ? "true" : "false");
    settings.set("chains", "4");
    auto in = integrators::make_integrator("mlt", settings);
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.seed = 9000 + uint64_t(r);
    opt.threads = 2;
    opt.max_depth = 6;
    opt.quiet = true;
    auto res = in->render(s, opt);
    b.push_back(res.info["b"].number());
    n += 200.0 + (large_step_b ? double(res.stats.get("mlt.large_steps")) : 0.0);
  }
  return {test::moments(b).var, n / kR};
}
}  // namespace

TEST_CASE("mlt: the normalisation b converges: its variance falls as 1 / (bootstrap + large steps)", "[stat]") {
  const auto s = glossy_box(16);
  const BStats a = b_spread(*s, 4, true), c = b_spread(*s, 32, true);
  const boost::math::fisher_f F(39, 39);
  const double ratio = a.var / c.var, expected = c.n / a.n;
  INFO("Var(b) ratio " << ratio << ", expected n ratio " << expected);
  CHECK(ratio / expected > boost::math::quantile(F, 0.005));
  CHECK(ratio / expected < boost::math::quantile(F, 0.995));
  CHECK(ratio > boost::math::quantile(F, 0.99));
  const BStats a0 = b_spread(*s, 4, false), c0 = b_spread(*s, 32, false);
  INFO("bootstrap only: Var(b) ratio " << a0.var / c0.var);
  CHECK_FALSE(a0.var / c0.var > boost::math::quantile(F, 0.99));
}
