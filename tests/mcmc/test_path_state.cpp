// The path-space state's evaluation (mcmc/path_state.h) on paths sampled by BDPT's real
// walks and connections: a lit box with a rough conductor and a smooth glass sphere
// (diffuse, glossy and Dirac vertices), a furnace sphere with a point light (a delta
// light: no s = 0 strategy) and an open scene under an environment and a sun (lights at
// infinity). For every connected path x of strategy (s, t), rebuilt as a PathState:
//  (1) evaluate_path() gives the same unweighted contribution C_s from the vertex
//      positions alone as connect() gave on the walks' subpaths (float round-off: the
//      walks' throughputs use the sampled directions, the state's the positions);
//  (2) the strategies it finds valid are the reference's (tests/integrators/
//      bidir_reference.h, written from Veach 1997, Eq. 10.9), and on paths without Dirac
//      vertices their 1 / lum C_s = p_s / lum F reproduce the reference's balance-
//      heuristic weights p_s / sum p_s': the state's C_s are the densities of every
//      strategy, which the bidirectional mutation's T sums. Through Dirac chains BDPT's
//      MIS (and the reference) count each Dirac-derived density as 1; that is a valid
//      partition of unity but not the ratio of the true densities (the generalized
//      geometry term of the chain differs from the segments' own conversions: watched
//      0.70 vs 0.75 on a path through the glass sphere), while each C_s is the strategy's
//      own unbiased value F / p_s, checked there by (1).
// A state that lets the camera walk "hit" a directional light (s = 0) was seen failing (2)
// (471 support mismatches under the sun) while writing this test; the RR factors of
// the walks must be divided out for (1) (C_s has no Russian roulette).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "mcmc/path_state.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/bidir_reference.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using pathspace::BidirVertex;

namespace {

struct Outcome {
  int64_t paths = 0, failed = 0, dirac = 0, multi = 0, support_mismatch = 0;
  double max_value_error = 0, max_weight_error = 0;
};

Outcome check(const scene::Scene& scene, int samples) {
  Outcome o;
  mcmc::PathState state;
  mcmc::PathSides sides;
  test::for_each_connection(scene, 6, samples, 11, pathspace::MisConfig{},
                            [&](int, const std::vector<BidirVertex>& light, const std::vector<BidirVertex>& cam, int s,
                                int t, const pathspace::Connection& con, const std::vector<BidirVertex>& x) {
    ++o.paths;
    mcmc::path_of_strategy(light.data(), s, cam.data(), t, state.v);
    if (!mcmc::evaluate_path(scene, state, sides) || !(state.inv_c[size_t(s)] > 0.0)) {
      ++o.failed;
      return;
    }
    // The walks' throughputs carry Russian roulette's 1 / q (rr_depth 3); C_s has none.
    double rr = 1.0;
    for (int i = 0; i + 1 < s; ++i) rr *= double(light[size_t(i)].rr_out);
    for (int j = 0; j + 1 < t; ++j) rr *= double(cam[size_t(j)].rr_out);
    const double lum = double(luminance(con.value)) * rr;
    o.max_value_error = std::max(o.max_value_error, std::abs(1.0 / state.inv_c[size_t(s)] - lum) / lum);
    const test::Reference ref = test::reference(scene, x, false);
    double sum = 0;
    int valid = 0;
    bool dirac = false;
    for (const auto& v : ref.x) dirac = dirac || test::is_dirac(v);
    o.dirac += dirac;
    for (size_t i = 0; i < state.inv_c.size(); ++i) {
      sum += state.inv_c[i];
      valid += state.inv_c[i] > 0.0;
      if ((state.inv_c[i] > 0.0) != bool(ref.valid[i])) ++o.support_mismatch;
    }
    o.multi += valid >= 3;
    if (dirac) return;  // the reference's Dirac convention is not a density ratio (see the top)
    for (size_t i = 0; i < state.inv_c.size(); ++i)
      o.max_weight_error = std::max(o.max_weight_error, std::abs(state.inv_c[i] / sum - ref.weight[i]));
  });
  return o;
}

}  // namespace

TEST_CASE("path state: C_s of every strategy from the vertices alone, consistent with BDPT", "[unit]") {
  const auto box = test::lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                             scene::ConductorFresnel{},
                                                                             scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                                 scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
  const auto furnace = test::furnace_sphere(0.5f, 0.5f, 1.0f, 16);
  const auto sky = test::env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                          scene::ConductorFresnel{},
                                                          scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                                    16, 2.0f);
  for (const auto* s : {box.get(), furnace.get(), sky.get()}) {
    const Outcome o = check(*s, s == sky.get() ? 1000 : 300);
    std::printf("path state: %lld paths (%lld through Dirac vertices, %lld with >= 3 strategies), %lld not evaluated, "
                "%lld support mismatches, max rel |C_s - C| %.3g, max |w_balance - w_ref| %.3g\n",
                (long long)o.paths, (long long)o.dirac, (long long)o.multi, (long long)o.failed,
                (long long)o.support_mismatch, o.max_value_error, o.max_weight_error);
    REQUIRE(o.paths > 500);
    CHECK(o.failed == 0);
    CHECK(o.support_mismatch == 0);
    CHECK(o.max_value_error < 1e-4);  // round-off of positions vs sampled directions: 1.2e-5 seen
    CHECK(o.max_weight_error < 2e-4);
    if (s == box.get()) CHECK(o.dirac > 20);
  }
}
