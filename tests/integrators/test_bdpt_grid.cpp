// bdpt on grid media (issue 15; pathspace/bidir_media.h): delta tracking in the walks,
// ratio tracking on the connections, deterministic stand-ins for the MIS densities. The
// scene of test_volpath_grid: an index-matched sphere of smoke under a uniform environment
// above a diffuse floor (.vol files written here, loaded through the YAML loader).
//  (a) a constant-density-1 grid against the same homogeneous medium (grey sigma_t 2,
//      albedo (0.9, 0.7, 0.5)), both by bdpt: the image mean and the 8x8-block means
//      agree (Welch per statistic, Sidak over the 17, family-wise 1%), 16 runs x 32 spp;
//  (b) the planted BidirFault::connection_without_ratio_tracking (grid media pass with
//      Tr = 1 on connections and light tracing) rejected by the same test;
//  (c) a ramp grid (density 0 .. 3 along x), where the MIS stand-ins differ from the true
//      densities, against volpath on the same grid: the estimator stays unbiased (and
//      the fault of (b) is rejected there too);
//  (d) the counters: delta tracking and ratio tracking run on grid scenes and never on
//      the homogeneous one; check_scene_support accepts bdpt on a grid scene.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/integrator.h"
#include "integrators/volpath/volpath_integrator.h"
#include "tests/integrators/grid_ball_support.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {

constexpr int kBlock = 8, kRuns = 16, kSpp = 32;

struct Runs {
  std::vector<std::vector<double>> stats;  // [statistic][run]
  int64_t grid_flights = 0, ratio_tracking = 0;
  double seconds = 0;
};

// kRuns renders with seeds seed0, seed0 + 1, ...; bdpt, or volpath if `volpath`.
Runs runs(const scene::Scene& s, pathspace::BidirFault fault, uint64_t seed0, bool volpath = false) {
  Runs r;
  for (int k = 0; k < kRuns; ++k) {
    const integrators::RenderOptions opt = test::grid_render_options(kSpp, seed0 + uint64_t(k));
    integrators::RenderResult res;
    if (volpath) {
      res = integrators::VolpathIntegrator(integrators::VolpathSettings{}).render(s, opt);
    } else {
      integrators::BdptSettings b;
      b.mis.fault = fault;
      res = integrators::BdptIntegrator(b).render(s, opt);
      r.grid_flights += res.stats.get("bdpt.grid_flights");
      r.ratio_tracking += res.stats.get("bdpt.ratio_tracking");
    }
    r.seconds += res.wall_seconds;
    const auto b = test::image_blocks(res.layers[0].image, kBlock);
    if (r.stats.empty()) r.stats.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i) r.stats[i].push_back(b[i]);
  }
  return r;
}

}  // namespace

TEST_CASE("bdpt: a grid medium renders as the homogeneous one and as volpath renders it", "[stat]") {
  const test::GridBallScenes scenes("bdpt_grid");
  const auto& homogeneous = scenes.homogeneous;
  const auto& grid = scenes.grid;
  const auto& ramp = scenes.ramp;
  REQUIRE(grid->media()[0].heterogeneous());
  REQUIRE(ramp->media()[0].heterogeneous());
  integrators::Settings settings;
  CHECK_NOTHROW(integrators::check_scene_support(*integrators::make_integrator("bdpt", settings), *grid));

  using pathspace::BidirFault;
  const Runs ref = runs(*homogeneous, BidirFault::none, 100);
  const Runs a = runs(*grid, BidirFault::none, 200);
  const Runs bad = runs(*grid, BidirFault::connection_without_ratio_tracking, 300);
  const double ok_ratio = test::sidak_welch(a.stats, ref.stats, 0.01);
  const double bad_ratio = test::sidak_welch(bad.stats, ref.stats, 0.01);
  std::printf("[bdpt grid] constant grid: image mean %.4f vs homogeneous %.4f: worst |t|/crit %.2f (mean and %zu "
              "blocks); connections without ratio tracking %.2f (mean %.4f); delta-tracked flights %lld, ratio-"
              "tracking estimates %lld; %.1f s vs %.1f s homogeneous\n",
              test::moments(a.stats[0]).mean, test::moments(ref.stats[0]).mean, ok_ratio, a.stats.size() - 1,
              bad_ratio, test::moments(bad.stats[0]).mean, (long long)a.grid_flights, (long long)a.ratio_tracking,
              a.seconds, ref.seconds);
  CHECK(ok_ratio < 1.0);
  CHECK(bad_ratio > 1.0);
  CHECK(a.grid_flights > 0);
  CHECK(a.ratio_tracking > 0);
  CHECK(ref.grid_flights == 0);  // no grid code without grid media
  CHECK(ref.ratio_tracking == 0);

  const Runs b = runs(*ramp, BidirFault::none, 400);
  const Runs v = runs(*ramp, BidirFault::none, 500, true);
  const Runs ramp_bad = runs(*ramp, BidirFault::connection_without_ratio_tracking, 600);
  const double ramp_ratio = test::sidak_welch(b.stats, v.stats, 0.01);
  const double ramp_bad_ratio = test::sidak_welch(ramp_bad.stats, v.stats, 0.01);
  std::printf("[bdpt grid] ramp grid: image mean %.4f vs volpath %.4f (relative se %.2f%%): worst |t|/crit %.2f; "
              "connections without ratio tracking %.2f\n",
              test::moments(b.stats[0]).mean, test::moments(v.stats[0]).mean,
              100.0 * std::sqrt(test::moments(b.stats[0]).var / double(kRuns)) / test::moments(b.stats[0]).mean,
              ramp_ratio, ramp_bad_ratio);
  CHECK(ramp_ratio < 1.0);
  CHECK(ramp_bad_ratio > 1.0);
}
