// `mlt --set mutations=path` (path-space MLT: Veach's bidirectional mutation alone, each
// perturbation with it (the bidirectional mutation keeps the chain ergodic), `veach` and
// `memlt`) against the reference path tracer
// on two small lit boxes: one with
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
// The image mean of a path-space render is b (every splat has luminance 1), so the mean
// test is a test of the BDPT seeder's b; the blocks test where the chains spend time.
// No negative control of the caustic perturbation's own terms is here: its angles are
// small (a fraction of a pixel to ~15 pixels), so its density corrections (the emission
// or BSDF density at x_l, the Dirac lobe probabilities) change by well under 1% per
// step; dropping the emission density was watched passing (worst 0.75) on the glass box.
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/mlt/mlt_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/block_stats.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 10, kDepth = 6;

struct Variant {
  const char* label;
  const char* mutators;
  mcmc::BidirMutationFault bidir_fault = mcmc::BidirMutationFault::none;
  const char* direct_spp = "0";  // auto; "-1": the chains render direct light too
};

test::BlockStats mlt_path_stats(const scene::Scene& s, const Variant& v, double* acceptance, int depth) {
  test::BlockStats st;
  for (int r = 0; r < kRuns; ++r) {
    integrators::Settings settings;
    settings.set("mutations", "path");
    settings.set("mutators", v.mutators);
    settings.set("bootstrap", "20000");
    settings.set("direct_spp", v.direct_spp);
    integrators::MltSettings m = integrators::MltSettings::read(settings);
    m.path_fault = v.bidir_fault;
    integrators::MltIntegrator in(m, settings.to_json());
    auto res = in.render(s, test::quiet_options(256, 500 + uint64_t(r), depth));
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

// Worst |t|/crit of variant v against the PT runs (printed).
double worst(const char* scene_name, const scene::Scene& s, const test::BlockStats& pt, const Variant& v,
             int depth = kDepth) {
  double acceptance = 0, first = 0;
  const test::BlockStats mlt = mlt_path_stats(s, v, &acceptance, depth);
  const double w = test::worst_welch(mlt, pt, 0.01, &first);
  const test::Moments a = test::moments(mlt[0]), b = test::moments(pt[0]);
  std::printf("mlt path [%s, %s]: mean %.5f +- %.5f vs PT %.5f +- %.5f; |t|/crit mean %.2f, worst block %.2f; "
              "acceptance %.3f\n",
              scene_name, v.label, a.mean, std::sqrt(a.var / kRuns), b.mean, std::sqrt(b.var / kRuns), first, w,
              acceptance);
  return w;
}

}  // namespace

TEST_CASE("mlt mutations=path: the bidirectional mutation and the perturbations agree with the path tracer", "[stat]") {
  using BF = mcmc::BidirMutationFault;
  {
    const auto s = test::lit_box(rough_conductor(), nullptr, kRes);
    const test::BlockStats pt = test::path_block_stats(*s, kRuns, 64, kDepth, kBlock);
    CHECK(worst("glossy box", *s, pt, {"bidir, direct light by the chains", "bidir", BF::none, "-1"}) < 1.0);
    CHECK(worst("glossy box", *s, pt, {"veach", "veach"}) < 1.0);
    CHECK(worst("glossy box", *s, pt, {"bidir, fault: sampled split only", "bidir", BF::sampled_split_only, "-1"}) > 1.0);
  }
  {
    const auto s = test::lit_box(rough_conductor(), scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx),
                                 kRes);
    const test::BlockStats pt = test::path_block_stats(*s, kRuns, 64, kDepth, kBlock);
    CHECK(worst("glossy + glass box", *s, pt, {"bidir + lens", "bidir,lens"}) < 1.0);
    CHECK(worst("glossy + glass box", *s, pt, {"bidir + caustic", "bidir,caustic"}) < 1.0);
    CHECK(worst("glossy + glass box", *s, pt, {"veach", "veach"}) < 1.0);
    CHECK(worst("glossy + glass box", *s, pt, {"bidir + manifold", "bidir,manifold"}) < 1.0);
    CHECK(worst("glossy + glass box", *s, pt, {"memlt", "memlt"}) < 1.0);
    CHECK(worst("glossy + glass box", *s, pt,
                {"veach, fault: sampled split only", "veach", BF::sampled_split_only, "-1"}) > 1.0);

  }
}

TEST_CASE("mlt mutations=path: deterministic per seed and chain count, whatever the thread count", "[unit]") {
  const auto s = test::lit_box(rough_conductor(), nullptr, 16);
  auto render = [&](uint64_t seed, int threads) {
    integrators::Settings settings;
    settings.set("mutations", "path");
    settings.set("bootstrap", "2000");  // default mutators: veach
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
  CHECK(a.stats.get("mlt.path.bidir.proposed") + a.stats.get("mlt.path.lens.proposed") +
            a.stats.get("mlt.path.caustic.proposed") + a.stats.get("mlt.path.stuck") ==
        8 * 16 * 16);
  CHECK(a.stats.get("mlt.path.lens.proposed") > 0);
  CHECK(a.stats.get("mlt.path.caustic.proposed") > 0);
}

// The caustic box (tests/support/test_scenes.h): the floor is lit only through a glass
// sphere (L S S D E), so every manifold perturbation from the pinhole walks a two-vertex
// refractive chain pinned at the light, whose Jacobian varies with the focusing (watched:
// ~36k walked chains per run of 262k mutations). Leaving the chain's Jacobian ratio out
// of the manifold perturbation's ratio was NOT detected here (worst |t|/crit 0.50): the
// vMF steps are small (lambda = 50), so the ratio is ~1 per step and the bidirectional
// mutation's large steps dominate the equilibrium at this power; the Jacobian itself
// is G-BDPT's (gradients/bidir_chain.h), checked against finite differences there.
TEST_CASE("mlt mutations=path: the manifold perturbation on a caustic agrees with the path tracer", "[stat]") {
  const auto s = test::caustic_box(kRes);
  const test::BlockStats pt = test::path_block_stats(*s, kRuns, 256, kDepth, kBlock);
  CHECK(worst("caustic box", *s, pt, {"bidir + manifold", "bidir,manifold"}) < 1.0);
}

// Two glass spheres, paths up to 10 segments: the camera sees through one sphere a floor
// lit through the other (E S S D S S D ..), where the multi-chain perturbation applies.
TEST_CASE("mlt mutations=path: Veach's mutations with the multi-chain perturbation agree with the path tracer", "[stat]") {
  const auto glass = scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx);
  const auto s = test::lit_box(glass, glass, kRes);
  const test::BlockStats pt = test::path_block_stats(*s, kRuns, 64, 10, kBlock);
  CHECK(worst("two glass spheres", *s, pt, {"bidir + multichain", "bidir,multichain"}, 10) < 1.0);
}

TEST_CASE("mlt mutations=path: replay=CHAIN:STEP re-runs one chain to a step, the same each time", "[unit]") {
  const auto s = test::lit_box(rough_conductor(), scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
  auto replay = [&](const char* at) {
    integrators::Settings settings;
    settings.set("bootstrap", "2000");
    settings.set("replay", at);
    auto in = integrators::make_integrator("memlt", settings);
    auto res = in->render(*s, test::quiet_options(4, 21, kDepth));
    return res.info["replay"];
  };
  core::Json a = replay("2:300"), b = replay("2:300"), c = replay("2:301"), d = replay("3:300");
  CHECK(a.dump() == b.dump());
  CHECK(a.dump() != c.dump());  // one more step, another record (the comparison can fail)
  CHECK(a.dump() != d.dump());  // another chain
  CHECK(a["state"]["depth"].number() >= 1);
  CHECK(a["state"]["lum_c_ref"].number() > 0);
  CHECK(a.dump().find("\"outcome\"") != std::string::npos);
  CHECK(a.dump().find("\"vertices\"") != std::string::npos);
}
