// VCM (`vcm`) against PT and BDPT in expectation. Image mean and 4x4-pixel block means of
// independent renders (fixed seeds), Welch t-tests Sidak-corrected over the 17 statistics
// at a family-wise level of 1% (tests/support/welch.h), thresholds from the run-to-run
// spread:
//  * mode=bpt and mode=lt are unbiased: against PT on the lit box with a rough conductor
//    and a smooth glass sphere (glossy and Dirac vertices, caustics), bpt and vcm also
//    under an environment and a directional light (light subpaths from infinity);
//  * mode=vcm, vm and ppm are consistent: at a small merging radius (0.2% of the scene
//    radius, shrinking with alpha = 0.75) their bias is below the test's resolution;
//  * merging is consistent: at a fixed radius of 30% of the scene radius the same test
//    rejects bidirectional photon mapping (the kernel's blur darkens the image by ~4%,
//    |t|/crit 4.6), at 3% it does not (0.6): the statistics resolve the merging bias, and
//    it falls with the radius.
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/vcm/vcm_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/quiet_options.h"
#include "tests/support/test_scenes.h"
#include "tests/support/block_stats.h"
#include "tests/support/welch.h"

using namespace dp;
using namespace dp::test;

namespace {
constexpr int kRes = 16, kBlock = 4, kRuns = 10, kDepth = 5;
constexpr double kAlpha = 0.01;

using Stats = BlockStats;

void add_run(Stats& st, const core::Image& img) { add_block_run(st, img, kBlock); }

Stats path_stats(const scene::Scene& s, int spp) { return path_block_stats(s, kRuns, spp, kDepth, kBlock); }

Stats vcm_stats(const scene::Scene& s, int iterations, const integrators::VcmSettings& settings) {
  Stats st;
  for (int r = 0; r < kRuns; ++r) {
    integrators::VcmIntegrator vcm(settings);
    const auto res = vcm.render(s, quiet_options(iterations, 7000 + uint64_t(r), kDepth));
    REQUIRE(res.stats.get("vcm.nan_dropped") == 0);
    REQUIRE(res.stats.get("vcm.iterations") == iterations);
    add_run(st, res.layers[0].image);
  }
  return st;
}

double verdict(const std::string& what, const Stats& b, const Stats& p) {
  const double worst = sidak_welch(b, p, kAlpha);
  const Moments mb = moments(b[0]), mp = moments(p[0]);
  const double se = std::sqrt(mb.var / double(mb.n) + mp.var / double(mp.n));
  std::printf("vcm vs path [%s]: mean %.5f vs %.5f (z %.2f, rel. se %.2f%%), worst |t|/crit over 17 stats %.2f%s\n",
              what.c_str(), mb.mean, mp.mean, (mb.mean - mp.mean) / se, 100 * se / mp.mean, worst,
              worst > 1 ? " -> rejected" : "");
  return worst;
}

integrators::VcmSettings mode(integrators::VcmMode m, float radius = 0.002f, float alpha = 0.75f) {
  integrators::VcmSettings s;
  s.mode = m;
  s.radius = radius;
  s.radius_alpha = alpha;
  return s;
}

std::unique_ptr<scene::Scene> glossy_glass_box() {
  return lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                             scene::ConductorFresnel{},
                                                             scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                 scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), kRes);
}

}  // namespace

TEST_CASE("vcm: modes bpt and lt are unbiased against PT", "[stat]") {
  const auto s = glossy_glass_box();
  CHECK(verdict("glossy + glass box, mode=bpt", vcm_stats(*s, 16, mode(integrators::VcmMode::bpt)), path_stats(*s, 64)) < 1.0);
  // Light tracing alone cannot reach the pinhole through a Dirac vertex (the glass
  // sphere): its test scene is the diffuse box, and the glass box must be rejected.
  const auto diffuse = lit_box(nullptr, nullptr, kRes);
  CHECK(verdict("diffuse box, mode=lt", vcm_stats(*diffuse, 64, mode(integrators::VcmMode::lt)), path_stats(*diffuse, 64)) < 1.0);
  CHECK(verdict("glossy + glass box, mode=lt (must miss the glass)", vcm_stats(*s, 64, mode(integrators::VcmMode::lt)),
                path_stats(*s, 64)) > 1.0);
}

TEST_CASE("vcm: modes vcm, vm and ppm agree with PT at a small radius", "[stat]") {
  const auto s = glossy_glass_box();
  const Stats p = path_stats(*s, 64);
  CHECK(verdict("glossy + glass box, mode=vcm", vcm_stats(*s, 16, mode(integrators::VcmMode::vcm, 0.02f)), p) < 1.0);
  CHECK(verdict("glossy + glass box, mode=vm", vcm_stats(*s, 32, mode(integrators::VcmMode::vm, 0.01f)), p) < 1.0);
  CHECK(verdict("glossy + glass box, mode=ppm", vcm_stats(*s, 32, mode(integrators::VcmMode::ppm, 0.01f)), p) < 1.0);
}

TEST_CASE("vcm: with the adaptive kernel, modes vcm and vm agree with PT at a small radius", "[stat]") {
  // Sun et al. 2017, Sec. 6: r^2 shrinks by 0.25^(10 tau) per camera vertex, so merges past
  // the walls use kernels ~1e-3 r wide: each kernel's own normalisation and eta_k in the
  // MIS must match for the mean to hold (vm: merges only, every depth).
  const auto s = glossy_glass_box();
  const Stats p = path_stats(*s, 64);
  auto adaptive = [](integrators::VcmSettings v) {
    v.adaptive_kernel = true;
    return v;
  };
  CHECK(verdict("glossy + glass box, mode=vcm, adaptive kernel",
                vcm_stats(*s, 16, adaptive(mode(integrators::VcmMode::vcm, 0.02f))), p) < 1.0);
  CHECK(verdict("glossy + glass box, mode=vm, adaptive kernel",
                vcm_stats(*s, 32, adaptive(mode(integrators::VcmMode::vm, 0.01f))), p) < 1.0);
  // Two smoother conductors (alpha 0.1: r^2 x 0.25 past them): many merges happen one
  // vertex behind a sphere, with a kernel 4x smaller in area. (Measured: without the
  // kernel's own 1/(pi r_t^2) this case is rejected, |t|/crit 3.3; the box above is not,
  // as its shrunk merges sit behind diffuse walls and weigh ~1e-12.)
  auto conductor = [] {
    return scene::make_two_sided(scene::make_conductor(0.1f, 0.1f, scene::MicrofacetType::ggx,
                                                       scene::ConductorFresnel{},
                                                       scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
  };
  const auto mirrors = lit_box(conductor(), conductor(), kRes);
  CHECK(verdict("two glossy spheres, mode=vm, adaptive kernel",
                vcm_stats(*mirrors, 32, adaptive(mode(integrators::VcmMode::vm, 0.01f))), path_stats(*mirrors, 64)) < 1.0);
}

TEST_CASE("vcm: modes bpt and vcm agree with PT under an environment and a directional light", "[stat]") {
  // Light subpaths from a disk at infinity; merges whose photon's predecessor is the
  // light at infinity (directional density at y_0).
  const auto s = env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                  scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                            kRes, 2.0f);
  const Stats p = path_stats(*s, 64);
  CHECK(verdict("environment + sun, mode=bpt", vcm_stats(*s, 16, mode(integrators::VcmMode::bpt)), p) < 1.0);
  CHECK(verdict("environment + sun, mode=vcm", vcm_stats(*s, 16, mode(integrators::VcmMode::vcm, 0.02f)), p) < 1.0);
}

TEST_CASE("vcm: merging is consistent: a large fixed radius is biased, a shrinking one is not", "[stat]") {
  const auto s = glossy_glass_box();
  const Stats p = path_stats(*s, 64);
  auto fixed = [&](float r) {
    return verdict("glossy + glass box, mode=vm, fixed radius " + std::to_string(r),
                   vcm_stats(*s, 32, mode(integrators::VcmMode::vm, r, 1.0f)), p);
  };
  const double large = fixed(0.3f), small = fixed(0.03f);
  CHECK(large > 1.0);  // the test resolves the kernel's bias at 30% of the scene radius
  CHECK(small < 1.0);
  CHECK(small < large);
}
