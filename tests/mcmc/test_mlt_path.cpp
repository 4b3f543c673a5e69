// `mlt --set mutations=path` (path-space MLT with Veach's bidirectional mutation,
// mcmc/mut_bidir.h) against the reference path tracer on two small lit boxes: one with
// a rough conductor sphere (diffuse and glossy vertices), one adding a smooth glass sphere
// (Dirac chains: refraction in and out, caustics on the floor). K independent runs of
// each (fixed seeds): the run-to-run spread gives each estimator's standard error
// whatever the chains' autocorrelation (tests/support/welch.h). Welch tests of the image
// mean (1%) and every 8x8 block (Sidak, 1% family-wise) must pass; the same tests must
// reject the mutation with a wrong transition density:
//  * T(x -> y) summing only the sampled split instead of every split that could have
//    produced y (the split is not part of the state);
//  * the reverse move's discrete pmf evaluated on x instead of on y (its admissible left
//    ends and length distribution differ when the length changes).
// Watched: correct worst |t|/crit 0.46 (glossy) and 0.44 (glass); sampled split only
// 13.9 and 8.2; pmf from source 1.44 (glossy box).
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/mlt/mlt_integrator.h"
#include "scene/bsdfs.h"
#include "tests/support/block_stats.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 10, kDepth = 6;

test::BlockStats mlt_path_stats(const scene::Scene& s, int mpp, mcmc::BidirMutationFault fault, double* acceptance) {
  test::BlockStats st;
  for (int r = 0; r < kRuns; ++r) {
    integrators::Settings settings;
    settings.set("mutations", "path");
    settings.set("bootstrap", "20000");
    integrators::MltSettings m = integrators::MltSettings::read(settings);
    m.path_fault = fault;
    integrators::MltIntegrator in(m, settings.to_json());
    auto res = in.render(s, test::quiet_options(mpp, 500 + uint64_t(r), kDepth));
    *acceptance = res.info["acceptance_rate"].number();
    REQUIRE(res.stats.get("mlt.nan_dropped") == 0);
    test::add_block_run(st, res.layers[0].image, kBlock);
  }
  return st;
}

scene::BsdfPtr rough_conductor() {
  return scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
}

struct Case {
  const char* name;
  std::unique_ptr<scene::Scene> scene;
};

}  // namespace

TEST_CASE("mlt mutations=path: the bidirectional mutation agrees with the path tracer", "[stat]") {
  Case cases[] = {{"glossy box", test::lit_box(rough_conductor(), nullptr, kRes)},
                  {"glossy + glass box",
                   test::lit_box(rough_conductor(), scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx),
                                 kRes)}};
  for (const Case& c : cases) {
    const test::BlockStats pt = test::path_block_stats(*c.scene, kRuns, 64, kDepth, kBlock);
    double acceptance = 0, first = 0;
    const test::BlockStats mlt = mlt_path_stats(*c.scene, 256, mcmc::BidirMutationFault::none, &acceptance);
    const double worst = test::worst_welch(mlt, pt, 0.01, &first);
    const test::Moments a = test::moments(mlt[0]), b = test::moments(pt[0]);
    std::printf("mlt path [%s]: mean %.5f +- %.5f vs PT %.5f +- %.5f; |t|/crit mean %.2f, worst block %.2f; acceptance %.3f\n",
                c.name, a.mean, std::sqrt(a.var / kRuns), b.mean, std::sqrt(b.var / kRuns), first, worst, acceptance);
    CHECK(acceptance > 0.05);
    CHECK(worst < 1.0);
    // The pmf-from-source defect is weak (the admissible left ends differ only when the
    // length changes): watched worst |t|/crit 1.44 on the glossy box, 1.10 on the glass
    // box; tested on the first only, with that margin.
    for (const auto fault : {mcmc::BidirMutationFault::sampled_split_only, mcmc::BidirMutationFault::pmf_from_source}) {
      if (fault == mcmc::BidirMutationFault::pmf_from_source && &c != &cases[0]) continue;
      const test::BlockStats bad = mlt_path_stats(*c.scene, 256, fault, &acceptance);
      const double w = test::worst_welch(bad, pt, 0.01, &first);
      std::printf("mlt path [%s] fault %s: |t|/crit mean %.2f, worst block %.2f\n", c.name,
                  fault == mcmc::BidirMutationFault::sampled_split_only ? "sampled split only" : "pmf from source", first,
                  w);
      CHECK(w > 1.0);
    }
  }
}

TEST_CASE("mlt mutations=path: deterministic per seed and chain count, whatever the thread count", "[unit]") {
  const auto s = test::lit_box(rough_conductor(), nullptr, 16);
  auto render = [&](uint64_t seed, int threads) {
    integrators::Settings settings;
    settings.set("mutations", "path");
    settings.set("bootstrap", "2000");
    settings.set("chains", "4");
    auto in = integrators::make_integrator("mlt", settings);
    integrators::RenderOptions opt = test::quiet_options(8, seed, kDepth);
    opt.threads = threads;
    return in->render(*s, opt);
  };
  const auto a = render(7, 1), b = render(7, 2), c = render(8, 2);
  bool same = true, differs = false;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      same &= (a.layers[0].image(x, y) == b.layers[0].image(x, y)).all();
      differs |= !(a.layers[0].image(x, y) == c.layers[0].image(x, y)).all();
    }
  CHECK(same);
  CHECK(differs);  // another seed gives another image (the comparison can fail)
  CHECK(a.stats.get("mlt.mutations") == 8 * 16 * 16);
  CHECK(a.stats.get("mlt.path.proposed") == 8 * 16 * 16);
}
