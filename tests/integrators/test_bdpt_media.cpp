// BDPT in participating media (pathspace/bidir_media.h), MIS part. Paths sampled by the
// real walks and connections of test::media_box (a fog filling the box, an index-matched
// smoke ball, a glass ball holding a tinted medium: medium vertices, edges crossing
// index-matched boundaries, refractive boundaries). For every connected path x of
// strategy (s, t), x is cut into the subpaths of EVERY strategy s' (s' light vertices),
// their densities re-derived from the positions by recompute_densities (each edge
// re-traced through the boundaries for its free-flight factors), and connected again:
//  (1) the MIS weights of all strategies that can generate x sum to 1;
//  (2) the weight of (s, t) on those re-derived subpaths equals the weight on the
//      walk-generated ones (the walk's incremental free-flight factors agree with the
//      re-traced edges).
// Must reject BidirFault::reverse_pdf_without_free_flight (a connection's reverse
// densities without the free-flight factors): the sums move off 1.
// Grid media (test::grid_media_box: grid fog, a ramp-density grid smoke ball): the end
// factors are deterministic stand-ins from the sub-segments' endpoints (bidir_media.h),
// and the same checks (1), (2) and the fault's rejection must hold.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "tests/integrators/bidir_reference.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::pathspace;

namespace {

struct Outcome {
  double max_sum_error = 0, max_weight_error = 0;
  int64_t paths = 0, with_medium = 0, medium_connections = 0;
};

// Subpaths of split s' of the full path x (light end first), densities from positions.
void cut(const scene::Scene& scene, const std::vector<BidirVertex>& x, int sp, std::vector<BidirVertex>& light,
         std::vector<BidirVertex>& camera) {
  const int n = int(x.size());
  light.assign(x.begin(), x.begin() + sp);
  if (sp > 0) light[0].kind = BidirKind::light;  // s = 0: x_0 came from the camera walk
  camera.clear();
  for (int i = n - 1; i >= sp; --i) {
    BidirVertex v = x[size_t(i)];
    if (i == 0) v.kind = BidirKind::surface;  // s' = 0: the camera walk hit the light
    camera.push_back(v);
  }
  recompute_densities(scene, light, scene::TransportMode::importance);
  recompute_densities(scene, camera, scene::TransportMode::radiance);
}

Outcome check(const scene::Scene& scene, const MisConfig& config, int samples) {
  Outcome o;
  std::vector<BidirVertex> ls, cs;
  test::for_each_connection(scene, 6, samples, 11, MisConfig{config.heuristic, BidirFault::none},
                            [&](int, const std::vector<BidirVertex>&, const std::vector<BidirVertex>&, int s, int t,
                                const Connection& con, const std::vector<BidirVertex>& x) {
    const int n = int(x.size());
    bool medium = false;
    for (const auto& v : x) medium = medium || v.kind == BidirKind::medium;
    if (!medium) return;
    ++o.paths;
    ++o.with_medium;
    if ((s > 0 && x[size_t(s - 1)].kind == BidirKind::medium) || x[size_t(s)].kind == BidirKind::medium)
      ++o.medium_connections;
    double sum = 0;
    for (int sp = 0; sp < n; ++sp) {
      cut(scene, x, sp, ls, cs);
      Connection c;
      if (!connect(scene, ls.data(), sp, cs.data(), n - sp, config, c)) continue;
      sum += double(c.weight);
      if (sp == s) o.max_weight_error = std::max(o.max_weight_error, std::abs(double(c.weight) - double(con.weight)));
    }
    o.max_sum_error = std::max(o.max_sum_error, std::abs(sum - 1.0));
    (void)t;
  });
  return o;
}

void report(const char* what, const Outcome& o) {
  std::printf("bdpt media MIS %s: %lld paths with medium vertices (%lld connect at one), max |sum - 1| %.2e, "
              "max |w_walk - w_rederived| %.2e\n",
              what, (long long)o.paths, (long long)o.medium_connections, o.max_sum_error, o.max_weight_error);
}

}  // namespace

TEST_CASE("bdpt in media: MIS weights over all strategies of a path sum to 1", "[unit]") {
  const auto fog = test::media_box(true, 16);
  const auto balls = test::media_box(false, 16);
  constexpr double kTol = 5e-4;  // float densities and re-traced edge lengths, double sums
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance}) {
    for (const auto* s : {fog.get(), balls.get()}) {
      const Outcome o = check(*s, MisConfig{heuristic, BidirFault::none}, 400);
      report(heuristic == MisHeuristic::power ? "power" : "balance", o);
      REQUIRE(o.paths > 300);
      CHECK(o.medium_connections > 100);
      CHECK(o.max_sum_error < kTol);
      CHECK(o.max_weight_error < kTol);
    }
  }
}

TEST_CASE("bdpt in media: the MIS check rejects reverse densities without free-flight factors", "[unit]") {
  const auto fog = test::media_box(true, 16);
  const Outcome o = check(*fog, MisConfig{MisHeuristic::power, BidirFault::reverse_pdf_without_free_flight}, 400);
  report("fault: no free-flight factor", o);
  CHECK(o.max_sum_error > 0.05);
}

TEST_CASE("bdpt in grid media: MIS weights over all strategies of a path sum to 1", "[unit]") {
  const auto grid = test::grid_media_box(16);
  constexpr double kTol = 5e-4;
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance}) {
    const Outcome o = check(*grid, MisConfig{heuristic, BidirFault::none}, 400);
    report(heuristic == MisHeuristic::power ? "grid, power" : "grid, balance", o);
    REQUIRE(o.paths > 300);
    CHECK(o.medium_connections > 100);
    CHECK(o.max_sum_error < kTol);
    CHECK(o.max_weight_error < kTol);
  }
  const Outcome bad = check(*grid, MisConfig{MisHeuristic::power, BidirFault::reverse_pdf_without_free_flight}, 400);
  report("grid, fault: no free-flight factor", bad);
  CHECK(bad.max_sum_error > 0.05);
}
