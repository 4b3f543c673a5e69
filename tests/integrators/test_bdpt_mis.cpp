// BDPT MIS weights (pathspace/bidir_mis.h) on paths sampled by the real subpath walks and
// connections of small scenes (lit box with a rough conductor and a smooth glass sphere:
// diffuse, glossy and Dirac vertices; furnace sphere with an emissive inner surface and a
// point light: a delta-position light; an open scene under a textured environment and a
// directional light: lights at infinity). For every connected path x of strategy (s, t):
//  (1) the weights the library computes for x as sampled by EVERY strategy (s', t') that
//      can generate it sum to 1 (to float precision), for the power and the balance
//      heuristic. The subpaths of each split (s', t') are rebuilt from x's vertices with
//      densities from a test-local reference written straight from Veach 1997, Eq. 10.9
//      (per-vertex densities from the light end and from the camera end); the library
//      recomputes the connection densities itself;
//  (2) the weight on the walk-generated subpaths equals the reference weight
//      p_s^b / sum p_s'^b computed from those full-path density products.
// Dirac-derived densities are 1 in the reference (they cancel between the strategies
// that exist; the library stores 0 and remaps it to 1).
// Both must reject the deliberate defects BidirFault::mis_without_light_tracing (sums
// exceed 1) and BidirFault::reverse_pdf_without_cosine.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/shapes/shape.h"
#include "tests/integrators/bidir_reference.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::pathspace;
using namespace dp::test;

namespace {

struct Outcome {
  double max_sum_error = 0, max_weight_error = 0;
  int64_t paths = 0, multi = 0, with_dirac = 0, light_tracing = 0, infinite = 0;
};

Outcome check_scene(const scene::Scene& scene, const MisConfig& config, int samples, uint64_t seed) {
  Outcome o;
  const bool power = config.heuristic == MisHeuristic::power;
  const int max_depth = 6;
  std::vector<BidirVertex> ls, cs;
  for_each_connection(scene, max_depth, samples, seed, config,
                      [&](int, const std::vector<BidirVertex>&, const std::vector<BidirVertex>&, int s, int t,
                          const Connection& con, const std::vector<BidirVertex>& x) {
    const Reference ref = reference(scene, x, power);
    ++o.paths;
    o.light_tracing += t == 1;
    o.infinite += at_infinity(ref.x[0]);
    int valid = 0;
    bool dirac = false;
    for (const auto& v : ref.x) dirac = dirac || is_dirac(v);
    o.with_dirac += dirac;
    double sum = 0;
    for (int sp = 0; sp < int(ref.x.size()); ++sp) {
      if (!ref.valid[size_t(sp)]) continue;
      ++valid;
      split(ref, sp, ls, cs);
      sum += double(mis_weight(scene, ls.data(), sp, cs.data(), int(ref.x.size()) - sp, config));
    }
    o.multi += valid >= 3;
    o.max_sum_error = std::max(o.max_sum_error, std::abs(sum - 1.0));
    o.max_weight_error = std::max(o.max_weight_error, std::abs(double(con.weight) - ref.weight[size_t(s)]));
  });
  return o;
}

std::unique_ptr<scene::Scene> glossy_glass_box() {
  return test::lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                   scene::ConductorFresnel{},
                                                                   scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                       scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
}

void report(const char* what, const Outcome& o) {
  std::printf("bdpt mis [%s]: %lld paths (%lld with >= 3 strategies, %lld through a Dirac vertex, %lld light-traced, "
              "%lld from a light at infinity), max |sum w - 1| %.3g, max |w - w_ref| %.3g\n",
              what, (long long)o.paths, (long long)o.multi, (long long)o.with_dirac, (long long)o.light_tracing,
              (long long)o.infinite,
              o.max_sum_error, o.max_weight_error);
}

}  // namespace

TEST_CASE("bdpt: MIS weights over all strategies of a path sum to 1", "[unit]") {
  const auto box = glossy_glass_box();
  const auto furnace = test::furnace_sphere(0.5f, 0.5f, 1.0f, 16);
  // Lights at infinity: a textured environment and a directional light.
  const auto sky = test::env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                          scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                                    16, 2.0f);
  constexpr double kTol = 2e-4;  // float densities, double sums
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance}) {
    const char* hname = heuristic == MisHeuristic::power ? "power" : "balance";
    for (const auto* s : {box.get(), furnace.get(), sky.get()}) {
      const Outcome o = check_scene(*s, MisConfig{heuristic, BidirFault::none}, s == sky.get() ? 1000 : 300, 7);
      report(hname, o);
      REQUIRE(o.paths > 500);
      CHECK(o.multi > 100);
      CHECK(o.max_sum_error < kTol);
      CHECK(o.max_weight_error < kTol);
    }
    CHECK(check_scene(*box, MisConfig{heuristic, BidirFault::none}, 300, 7).with_dirac > 20);
    CHECK(check_scene(*sky, MisConfig{heuristic, BidirFault::none}, 1000, 7).infinite > 500);
  }
}

TEST_CASE("bdpt: the MIS check rejects weights without light tracing or with a missing cosine", "[unit]") {
  const auto box = glossy_glass_box();
  for (const auto fault : {BidirFault::mis_without_light_tracing, BidirFault::reverse_pdf_without_cosine}) {
    const Outcome o = check_scene(*box, MisConfig{MisHeuristic::power, fault}, 300, 7);
    report(fault == BidirFault::mis_without_light_tracing ? "fault: no light tracing" : "fault: no cosine", o);
    CHECK(o.max_sum_error > 0.05);
  }
}
