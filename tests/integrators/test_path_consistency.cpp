// Light sampling (NEE + MIS) and pure BSDF sampling are two unbiased estimators of the
// same image: their block means must agree within the noise (Welch t-test per block,
// Šidák-corrected over blocks). A wrong MIS weight or pdf shows up as a bias here.
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>

#include "integrators/integrator.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 12;

// Block means (luminance-free: channel sum) of kRuns independent renders.
std::vector<std::vector<double>> block_means(const scene::Scene& s, bool nee, uint64_t seed0) {
  integrators::Settings settings;
  settings.set("nee", nee ? "true" : "false");
  auto pt = integrators::make_integrator("path", settings);
  const int nb = kRes / kBlock;
  std::vector<std::vector<double>> out(size_t(nb * nb));
  for (int r = 0; r < kRuns; ++r) {
    integrators::RenderOptions opt;
    opt.spp = 16;
    opt.seed = seed0 + uint64_t(r);
    opt.threads = 2;
    opt.max_depth = 6;
    opt.quiet = true;
    const core::Image img = pt->render(s, opt).layers[0].image;
    for (int by = 0; by < nb; ++by)
      for (int bx = 0; bx < nb; ++bx) {
        double sum = 0;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) sum += double(img(x, y).sum());
        out[size_t(by * nb + bx)].push_back(sum / (kBlock * kBlock));
      }
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

// Largest |t| over blocks relative to the Šidák-corrected critical value (< 1 passes).
double worst_ratio(const scene::Scene& s, double scale_b) {
  const auto a = block_means(s, true, 100), b = block_means(s, false, 200);
  const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(a.size()));
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const Moments ma = moments(a[i]);
    Moments mb = moments(b[i]);
    mb.mean *= scale_b;
    mb.var *= scale_b * scale_b;
    const double va = ma.var / kRuns, vb = mb.var / kRuns;
    if (va + vb <= 0) continue;
    const double t = (ma.mean - mb.mean) / std::sqrt(va + vb);
    const double dof = (va + vb) * (va + vb) / (va * va / (kRuns - 1) + vb * vb / (kRuns - 1));  // Welch-Satterthwaite
    const double crit = boost::math::quantile(boost::math::complement(boost::math::students_t(dof), alpha / 2));
    worst = std::max(worst, std::abs(t) / crit);
  }
  return worst;
}
}  // namespace

TEST_CASE("PT with NEE+MIS agrees with BSDF-only sampling (glossy + plastic spheres)", "[render]") {
  const auto s = test::lit_box(
      scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                  scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
      scene::make_two_sided(scene::make_phong(scene::constant_texture(Rgb::Constant(0.3f)),
                                              scene::constant_texture(Rgb::Constant(0.5f)), 40.0f)),
      kRes);
  const double r = worst_ratio(*s, 1.0);
  INFO("worst |t| / critical = " << r);
  REQUIRE(r < 1.0);
  // The same test rejects a 10% bias (so it can fail).
  REQUIRE(worst_ratio(*s, 1.1) > 1.0);
}
