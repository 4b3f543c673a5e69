// The volumetric path tracer (issue 15):
//  * the volumetric furnace: an index-matched ball of albedo-1 medium under a uniform
//    environment renders the environment's radiance (image-mean z-test per channel,
//    Sidak-corrected), camera outside and inside the medium, NEE on and off; the same
//    test rejects three real defects of the tracer (VolpathFault);
//  * on a scene without media volpath runs no medium code (counters) and its image
//    agrees with `path`'s (Welch t-test per block over independent runs);
//  * on a scene with media (smoke behind an index-matched boundary, a glass ball with a
//    medium inside, a fog filling the box) NEE + MIS and BSDF/phase sampling alone are
//    two estimators that must agree per block; a defect is rejected;
//  * `path` delegates to volpath on a scene with media (the same image, bit for bit).
#include <boost/math/distributions/normal.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <cstdio>

#include "integrators/integrator.h"
#include "integrators/volpath/volpath_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {

integrators::RenderOptions options(int spp, uint64_t seed, int max_depth) {
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = max_depth;
  opt.quiet = true;
  return opt;
}

integrators::RenderResult render(const scene::Scene& s, const std::string& name, bool nee, int spp, uint64_t seed,
                                 int max_depth) {
  integrators::Settings settings;
  settings.set("nee", nee ? "true" : "false");
  return integrators::make_integrator(name, settings)->render(s, options(spp, seed, max_depth));
}

integrators::RenderResult render_volpath(const scene::Scene& s, const integrators::VolpathSettings& vs, int spp,
                                         uint64_t seed, int max_depth) {
  integrators::VolpathIntegrator in(vs);
  return in.render(s, options(spp, seed, max_depth));
}

// Largest |z| over the channels of the image mean against `expected`: pixels are
// independent estimates of the same radiance, so the standard error of the mean is the
// pixels' standard deviation / sqrt(pixel count).
double furnace_z(const core::Image& img, const Rgb& expected) {
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    double s = 0, s2 = 0;
    for (const auto& p : img.pixels()) {
      s += double(p[c]);
      s2 += double(p[c]) * double(p[c]);
    }
    const double n = double(img.size()), mean = s / n, var = (s2 / n - mean * mean) * n / (n - 1);
    const double se = std::sqrt(var / n);
    if (!(se > 0)) return std::abs(mean - double(expected[c])) > 0 ? 1e300 : 0.0;
    worst = std::max(worst, std::abs(mean - double(expected[c])) / se);
  }
  return worst;
}

scene::HomogeneousMedium furnace_medium() {
  scene::HomogeneousMedium m;
  m.sigma_a = Rgb::Zero();                // albedo 1 in every channel
  m.sigma_s = Rgb(0.5f, 1.0f, 2.0f);      // spectral: the channel mixture's weights are exercised
  m.phase.type = scene::PhaseFunctionDesc::Type::hg;
  m.phase.g = 0.6f;
  return m;
}

const Rgb kEnv(1.0f, 0.8f, 0.6f);
constexpr int kFurnaceDepth = 1000;  // Russian roulette ends paths; truncation bias < 0.95^995

using BlockMeans = std::vector<std::vector<double>>;  // [block][run]
constexpr int kRes = 32, kBlock = 8, kRuns = 12, kSpp = 16, kDepth = 8;

void add_run(BlockMeans& out, const core::Image& img) {
  const int nb = kRes / kBlock;
  out.resize(size_t(nb * nb));
  for (int by = 0; by < nb; ++by)
    for (int bx = 0; bx < nb; ++bx) {
      double sum = 0;
      for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
        for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) sum += double(img(x, y).sum());
      out[size_t(by * nb + bx)].push_back(sum / (kBlock * kBlock));
    }
}

BlockMeans blocks(const std::function<core::Image(uint64_t seed)>& run, uint64_t seed0) {
  BlockMeans out;
  for (int r = 0; r < kRuns; ++r) add_run(out, run(seed0 + uint64_t(r)));
  return out;
}

}  // namespace

TEST_CASE("volpath: the volumetric furnace renders exactly the environment", "[stat]") {
  constexpr int kFurnaceRes = 40, kFurnaceSpp = 16;
  // 4 configurations x 3 channels at 1% family-wise (Sidak), two-sided.
  const double z_crit = boost::math::quantile(boost::math::normal(), 1.0 - (1.0 - std::pow(0.99, 1.0 / 12.0)) / 2.0);
  for (bool inside : {false, true})
    for (bool nee : {true, false}) {
      const auto s = test::medium_furnace(furnace_medium(), kEnv, inside, kFurnaceRes);
      const auto r = render(*s, "volpath", nee, kFurnaceSpp, inside ? 11 : 12, kFurnaceDepth);
      const double z = furnace_z(r.layers[0].image, kEnv);
      std::printf("[volpath furnace] camera %s, nee %d: worst |z| %.2f (crit %.2f); medium scatters %lld\n",
                  inside ? "inside" : "outside", int(nee), z, z_crit,
                  static_cast<long long>(r.stats.get("volpath.medium_scatter")));
      CHECK(z < z_crit);
      CHECK(r.stats.get("volpath.medium_scatter") > 0);
      CHECK(r.stats.get("volpath.nan_dropped") == 0);
      if (!inside) CHECK(r.stats.get("volpath.null_crossings") > 0);
    }
  // The same test rejects real defects of the tracer (VolpathFault, camera outside, NEE on):
  //  * NEE ignoring the transmittance along the shadow ray (too bright),
  //  * NEE at medium vertices weighted 1 while phase-sampled hits keep their MIS weight
  //    (environment light counted up to twice),
  //  * a segment that passes the medium weighted Tr instead of Tr / P(pass) (too dark).
  // Tried locally (not kept as a fault): the phase pdf halved in the MIS weight of
  // emitter hits after a medium vertex, rejected with |z| 27 (outside) and 53 (inside).
  const auto s = test::medium_furnace(furnace_medium(), kEnv, false, kFurnaceRes);
  for (auto fault : {integrators::VolpathFault::nee_without_transmittance, integrators::VolpathFault::medium_nee_without_mis,
                     integrators::VolpathFault::pass_without_probability}) {
    integrators::VolpathSettings vs;
    vs.fault = fault;
    const double z = furnace_z(render_volpath(*s, vs, kFurnaceSpp, 13, kFurnaceDepth).layers[0].image, kEnv);
    std::printf("[volpath furnace] fault %d: worst |z| %.2f\n", int(fault), z);
    CHECK(z > z_crit);
  }
}

TEST_CASE("volpath: without media it runs no medium code and agrees with path", "[stat]") {
  const auto s = test::lit_box(
      scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                  scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
      scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), kRes);
  REQUIRE_FALSE(s->caps().has_media);
  int64_t paths = 0, skipped = 0, medium_events = 0;
  bool media_info = true;
  const BlockMeans v = blocks(
      [&](uint64_t seed) {
        auto r = render(*s, "volpath", true, kSpp, seed, kDepth);
        paths += r.stats.get("volpath.paths");
        skipped += r.stats.get("volpath.media_skipped");
        medium_events += r.stats.get("volpath.medium_scatter") + r.stats.get("volpath.medium_pass") +
                         r.stats.get("volpath.null_crossings") + r.stats.get("volpath.shadow_null_crossings");
        media_info = media_info && r.info["media"].dump().find("true") != std::string::npos;
        return r.layers[0].image;
      },
      100);
  const BlockMeans p = blocks([&](uint64_t seed) { return render(*s, "path", true, kSpp, seed, kDepth).layers[0].image; }, 200);
  // Every path ran the variant compiled without medium code.
  CHECK(paths == int64_t(kRuns) * kRes * kRes * kSpp);
  CHECK(skipped == paths);
  CHECK(medium_events == 0);
  CHECK_FALSE(media_info);
  // Tried locally: volpath's surface NEE without |cos theta_o| is rejected (|t|/crit 11.9).
  const double worst = test::sidak_welch(v, p, 0.01);
  std::printf("[volpath vs path, no media] worst |t|/crit %.2f\n", worst);
  CHECK(worst < 1.0);
}

TEST_CASE("volpath: NEE + MIS and phase/BSDF sampling alone agree on a scene with media", "[stat]") {
  const auto s = test::media_box(true, kRes);
  REQUIRE(s->caps().has_media);
  integrators::RenderResult last;
  const BlockMeans on = blocks(
      [&](uint64_t seed) {
        last = render(*s, "volpath", true, kSpp, seed, kDepth);
        return last.layers[0].image;
      },
      300);
  const BlockMeans off = blocks([&](uint64_t seed) { return render(*s, "volpath", false, kSpp, seed, kDepth).layers[0].image; }, 400);
  // It did what the scene asks for: medium vertices, index-matched crossings by path and
  // shadow rays, surface vertices; no NaN.
  CHECK(last.stats.get("volpath.medium_scatter") > 0);
  CHECK(last.stats.get("volpath.medium_pass") > 0);
  CHECK(last.stats.get("volpath.null_crossings") > 0);
  CHECK(last.stats.get("volpath.shadow_null_crossings") > 0);
  CHECK(last.stats.get("volpath.surface_events") > 0);
  CHECK(last.stats.get("volpath.media_skipped") == 0);
  CHECK(last.stats.get("volpath.nan_dropped") == 0);
  CHECK(last.stats.get("volpath.fail.null_limit") == 0);
  const double worst = test::sidak_welch(on, off, 0.01);
  // A real defect is rejected: NEE without the fog's and the smoke's transmittance.
  // (Its power is limited: the phase pdf halved in the MIS weight, tried locally, passes
  // here at 0.40; the furnace rejects that one.)
  integrators::VolpathSettings vs;
  vs.fault = integrators::VolpathFault::nee_without_transmittance;
  const BlockMeans bad = blocks([&](uint64_t seed) { return render_volpath(*s, vs, kSpp, seed, kDepth).layers[0].image; }, 500);
  const double worst_bad = test::sidak_welch(bad, off, 0.01);
  std::printf("[volpath NEE vs no NEE, media box] worst |t|/crit %.2f; NEE without transmittance %.2f\n", worst,
              worst_bad);
  CHECK(worst < 1.0);
  CHECK(worst_bad > 1.0);
}

// Equiangular NEE (integrators/volpath/volpath_equiangular.cpp) adds a third technique for
// the direct light of medium vertices; with its MIS the image must not change: volpath with
// it against volpath without it (free-flight NEE and phase sampling only), per block. The
// same test must reject equiangular NEE weighted 1 (counted twice with the free-flight
// NEE). Runs from seed0, seed0 + 100 and seed0 + 200; returns the last run with it.
namespace {
struct EquiangularCheck {
  double worst = 0, worst_bad = 0;
  integrators::RenderResult last, last_off;
};
EquiangularCheck equiangular_check(const scene::Scene& s, uint64_t seed0) {
  integrators::VolpathSettings with, without, bad;
  without.equiangular = false;
  bad.fault = integrators::VolpathFault::equiangular_without_mis;
  EquiangularCheck r;
  auto run = [&](const integrators::VolpathSettings& vs, integrators::RenderResult* keep) {
    return [&s, vs, keep](uint64_t seed) {
      integrators::RenderResult res = render_volpath(s, vs, kSpp, seed, kDepth);
      core::Image img = res.layers[0].image;
      if (keep) *keep = std::move(res);
      return img;
    };
  };
  const BlockMeans on = blocks(run(with, &r.last), seed0), off = blocks(run(without, &r.last_off), seed0 + 100),
                   twice = blocks(run(bad, nullptr), seed0 + 200);
  r.worst = test::sidak_welch(on, off, 0.01);
  r.worst_bad = test::sidak_welch(twice, off, 0.01);
  CHECK(r.last.stats.get("volpath.equiangular.samples") > 0);
  CHECK(r.last.stats.get("volpath.nan_dropped") == 0);
  CHECK(r.last_off.stats.get("volpath.equiangular.samples") == 0);
  return r;
}
}  // namespace

// The media box with a point light added in the fog (Dirac case) besides the area light.
TEST_CASE("volpath: equiangular NEE with its MIS leaves the image unchanged", "[stat]") {
  const auto s = test::media_box(true, kRes, true, true);
  const EquiangularCheck r = equiangular_check(*s, 600);
  std::printf("[volpath equiangular vs free-flight NEE, media box + point light] worst |t|/crit %.2f; without MIS %.2f\n",
              r.worst, r.worst_bad);
  CHECK(r.worst < 1.0);
  CHECK(r.worst_bad > 1.0);
}

// Grid media (test::grid_media_box: a grid fog and a ramp-density grid ball): equiangular NEE
// with ratio-tracked Tr and the deterministic MIS stand-in for delta tracking's density
// (volpath_equiangular.cpp). Tried locally: its Tr(t) taken as 1 instead of ratio tracking's
// estimate is rejected at 2.81.
TEST_CASE("volpath: equiangular NEE in grid media leaves the image unchanged", "[stat]") {
  const auto s = test::grid_media_box(kRes);
  const EquiangularCheck r = equiangular_check(*s, 900);
  CHECK(r.last.stats.get("volpath.grid_flights") > 0);
  std::printf("[volpath equiangular vs free-flight NEE, grid media box] worst |t|/crit %.2f; without MIS %.2f\n", r.worst,
              r.worst_bad);
  CHECK(r.worst < 1.0);
  CHECK(r.worst_bad > 1.0);
}

TEST_CASE("volpath: path delegates to volpath on a scene with media", "[unit]") {
  const auto s = test::media_box(false, 16);
  auto p = render(*s, "path", true, 2, 9, kDepth);
  const auto v = render(*s, "volpath", true, 2, 9, kDepth);
  CHECK(p.info["delegated_to"].dump().find("\"volpath\"") != std::string::npos);
  CHECK(p.stats.get("volpath.paths") == 16 * 16 * 2);
  CHECK(p.stats.get("pt.paths") == 0);
  const auto& a = p.layers[0].image.pixels();
  const auto& b = v.layers[0].image.pixels();
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) REQUIRE((a[i] == b[i]).all());
}
