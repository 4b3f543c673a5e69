// The bookkeeping of every path-space mutation is symmetric (docs/memlt_plan.md, test A):
// for proposals y sampled from states x of running chains, the ratio of the move and the
// ratio of its reverse (made on y) satisfy
//   ratio(x -> y, rec) * ratio(y -> x, rec.reverse()) = 1
// to round-off, so f(x) T(x -> y) a(x -> y) = f(y) T(y -> x) a(y -> x) holds for the
// acceptance min(1, ratio) whatever the densities are. It cannot see a density that is
// wrong the same way in both directions (the image tests of test_mlt_path.cpp do), but it
// catches every term evaluated on the wrong path: the bidirectional mutation with the
// reverse pmf taken on x fails it. Scenes: a glossy + glass box (Dirac chains, caustics),
// a point-lit furnace (a delta light), a sky + sun scene (lights at infinity).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "mcmc/mut_bidir.h"
#include "mcmc/mut_caustic.h"
#include "mcmc/mut_lens.h"
#include "mcmc/mut_manifold.h"
#include "mcmc/mut_multichain.h"
#include "mcmc/path_chain.h"
#include "mcmc/path_seed.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {

struct Tally {
  int64_t pairs = 0, reverse_impossible = 0;
  double worst = 0;  // max |ratio * reverse ratio - 1|
};

// Runs a veach chain on `scene` and tries every suitable mutation at each visited state.
std::vector<Tally> check(const scene::Scene& scene, mcmc::BidirMutationFault fault, int steps, int max_depth = 6) {
  mcmc::BidirLengths lengths;
  lengths.k_max = max_depth + 2;
  const mcmc::BidirMutation bidir(scene, lengths, fault);
  const mcmc::LensPerturbation lens(scene);
  const mcmc::CausticPerturbation caustic(scene, lens.r1(), lens.r2());
  const mcmc::ManifoldPerturbation manifold(scene);
  const mcmc::MultiChainPerturbation multichain(scene, lens.r1(), lens.r2());
  const std::vector<const mcmc::Mutator*> all{&bidir, &lens, &caustic, &manifold, &multichain};
  mcmc::PathSeedOptions so;
  so.max_depth = max_depth;
  so.samples = 2000;
  so.seed = 3;
  const mcmc::PathSeeder seeder(scene, so);
  mcmc::PathState x, y;
  mcmc::PathSides sides;
  REQUIRE(seeder.select(0.37, x, sides));
  mcmc::PathChain chain({{&bidir, 1.0}, {&lens, 1.0}, {&caustic, 1.0}, {&manifold, 1.0}, {&multichain, 1.0}}, 5, 0);
  chain.start(x);
  core::Rng rng(9, 1);
  std::vector<Tally> out(all.size());
  for (int i = 0; i < steps; ++i) {
    chain.step();
    const mcmc::PathState& cur = chain.current();
    for (size_t m = 0; m < all.size(); ++m) {
      if (!all[m]->suitable(cur)) continue;
      mcmc::MutationRecord rec;
      if (all[m]->sample(cur, y, rec, rng, sides) != mcmc::ProposalStatus::ok) continue;
      const double fwd = all[m]->ratio(cur, y, rec);
      if (!(fwd > 0.0)) {
        ++out[m].reverse_impossible;
        continue;
      }
      const double back = all[m]->ratio(y, cur, rec.reverse());
      ++out[m].pairs;
      out[m].worst = std::max(out[m].worst, std::abs(fwd * back - 1.0));
    }
  }
  return out;
}

const char* kNames[] = {"bidir", "lens", "caustic", "manifold", "multichain"};

}  // namespace

TEST_CASE("path mutations: ratio(x -> y) * ratio(y -> x) = 1 for every mutation", "[unit]") {
  const auto conductor = scene::make_two_sided(scene::make_conductor(
      0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{}, scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
  const auto box = test::lit_box(conductor, scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
  const auto furnace = test::furnace_sphere(0.5f, 0.5f, 1.0f, 16);
  const auto sky = test::env_glossy(conductor, 16, 2.0f);
  const char* scene_names[] = {"glossy + glass box", "point-lit furnace", "sky + sun"};
  const scene::Scene* scenes[] = {box.get(), furnace.get(), sky.get()};
  for (int k = 0; k < 3; ++k) {
    const auto t = check(*scenes[k], mcmc::BidirMutationFault::none, 3000);
    for (size_t m = 0; m < t.size(); ++m) {
      std::printf("mutation symmetry [%s, %s]: %lld pairs, %lld with an impossible reverse, worst |r r' - 1| %.3g\n",
                  scene_names[k], kNames[m], (long long)t[m].pairs, (long long)t[m].reverse_impossible, t[m].worst);
      CHECK(t[m].worst < 1e-9);
    }
    CHECK(t[0].pairs > 300);
    if (k == 0) {
      CHECK(t[1].pairs > 300);
      CHECK(t[2].pairs > 100);
      CHECK(t[3].pairs > 300);
    }
  }
  // Two glass spheres and deep paths: the camera sees through one sphere a floor lit
  // through the other (E S S D S S D ..), the multi-chain perturbation's case.
  const auto glass = scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx);
  const auto two = test::lit_box(glass, glass, 16);
  const auto deep = check(*two, mcmc::BidirMutationFault::none, 6000, 10);
  for (size_t m = 0; m < deep.size(); ++m) {
    std::printf("mutation symmetry [two glass spheres, depth 10, %s]: %lld pairs, worst |r r' - 1| %.3g\n", kNames[m],
                (long long)deep[m].pairs, deep[m].worst);
    CHECK(deep[m].worst < 1e-9);
  }
  CHECK(deep[4].pairs > 50);
  // The reverse pmf evaluated on x breaks the symmetry wherever x's and y's admissible
  // left ends or lengths differ.
  const auto bad = check(*box, mcmc::BidirMutationFault::pmf_from_source, 3000);
  std::printf("mutation symmetry [glossy + glass box, bidir with the reverse pmf on x]: worst %.3g\n", bad[0].worst);
  CHECK(bad[0].worst > 0.01);
}
