// BDPT against the reference path tracer in expectation: image mean and 4x4-pixel block
// means of independent renders (fixed seeds), Welch t-tests Sidak-corrected over the 17
// statistics at a family-wise level of 1% (tests/support/welch.h), on a diffuse lit box
// and on a lit box with a rough conductor and a smooth glass sphere (glossy and Dirac
// vertices; caustics through the glass, which BDPT reaches by light tracing and PT by
// BSDF sampling), and on an open scene under a textured environment and a directional
// light (light subpaths from a disk at infinity): there the MIS that counts light tracing
// from the environment to the pinhole (a strategy no sample takes) must be rejected. Thresholds come from the run-to-run spread. The same test must reject BDPT with a real defect (BidirFault): the
// light-tracing strategy left out of the MIS sums, and reverse densities missing their
// cosine. In participating media (test::media_box: a fog filling the box, an
// index-matched smoke ball, a glass ball holding a tinted medium) against volpath (`path`
// delegates to it), rejecting connections without their transmittance and reverse
// densities without their free-flight factors.
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/bdpt/bdpt_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"
#include "tests/support/quiet_options.h"
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

Stats bdpt_stats(const scene::Scene& s, int spp, const integrators::BdptSettings& settings) {
  Stats st;
  for (int r = 0; r < kRuns; ++r) {
    integrators::BdptIntegrator bdpt(settings);
    const auto res = bdpt.render(s, quiet_options(spp, 5000 + uint64_t(r), kDepth));
    REQUIRE(res.stats.get("bdpt.nan_dropped") == 0);
    add_run(st, res.layers[0].image);
  }
  return st;
}

double verdict(const char* what, const Stats& b, const Stats& p) {
  const double worst = sidak_welch(b, p, kAlpha);
  const Moments mb = moments(b[0]), mp = moments(p[0]);
  const double se = std::sqrt(mb.var / double(mb.n) + mp.var / double(mp.n));
  std::printf("bdpt vs path [%s]: mean %.5f vs %.5f (z %.2f, rel. se %.2f%%), worst |t|/crit over 17 stats %.2f%s\n",
              what, mb.mean, mp.mean, (mb.mean - mp.mean) / se, 100 * se / mp.mean, worst,
              worst > 1 ? " -> rejected" : "");
  return worst;
}

void run_scene(const char* name, const scene::Scene& s, bool faults = true) {
  const Stats p = path_stats(s, 64);
  integrators::BdptSettings settings;
  for (const auto h : {pathspace::MisHeuristic::power, pathspace::MisHeuristic::balance}) {
    settings.mis.heuristic = h;
    const std::string what = std::string(name) + (h == pathspace::MisHeuristic::power ? ", power" : ", balance");
    CHECK(verdict(what.c_str(), bdpt_stats(s, 16, settings), p) < 1.0);
  }
  if (!faults) return;
  settings.mis.heuristic = pathspace::MisHeuristic::power;
  settings.mis.fault = pathspace::BidirFault::mis_without_light_tracing;
  CHECK(verdict((std::string(name) + ", fault: MIS without light tracing").c_str(), bdpt_stats(s, 16, settings), p) > 1.0);
  settings.mis.fault = pathspace::BidirFault::reverse_pdf_without_cosine;
  CHECK(verdict((std::string(name) + ", fault: reverse pdf without cosine").c_str(), bdpt_stats(s, 16, settings), p) > 1.0);
}
}  // namespace

TEST_CASE("bdpt: image mean agrees with PT on a diffuse lit box", "[stat]") {
  const auto s = lit_box(nullptr, nullptr, kRes);
  run_scene("diffuse box", *s);
}

TEST_CASE("bdpt: image mean agrees with PT on a box with glossy and glass spheres", "[stat]") {
  const auto s = lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                     scene::ConductorFresnel{},
                                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                         scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), kRes);
  run_scene("glossy + glass box", *s);
}

TEST_CASE("bdpt: image mean agrees with PT under an environment and a directional light", "[stat]") {
  const auto s = env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                  scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                            kRes, 2.0f);
  run_scene("environment + sun", *s, false);
  integrators::BdptSettings settings;
  settings.mis.heuristic = pathspace::MisHeuristic::balance;
  settings.mis.fault = pathspace::BidirFault::light_tracing_at_infinity;
  CHECK(verdict("environment + sun, balance, fault: light tracing at infinity", bdpt_stats(*s, 16, settings),
                path_stats(*s, 64)) > 1.0);
}

TEST_CASE("bdpt: image mean agrees with volpath in participating media", "[stat]") {
  for (const bool fog : {true, false}) {
    const auto s = media_box(fog, kRes);
    const char* name = fog ? "media box with fog" : "media box";
    const Stats p = path_stats(*s, 64);
    integrators::BdptSettings settings;
    CHECK(verdict(name, bdpt_stats(*s, 16, settings), p) < 1.0);
    if (!fog) continue;
    settings.mis.fault = pathspace::BidirFault::connection_without_transmittance;
    CHECK(verdict("media box with fog, fault: connection without transmittance", bdpt_stats(*s, 16, settings), p) > 1.0);
    settings.mis.fault = pathspace::BidirFault::reverse_pdf_without_free_flight;
    CHECK(verdict("media box with fog, fault: reverse pdf without free flight", bdpt_stats(*s, 16, settings), p) > 1.0);
  }
}
