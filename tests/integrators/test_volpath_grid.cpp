// volpath on a grid medium (issue 15; scene/media/grid_tracking.h): a sphere (index-
// matched boundary) of smoke under a uniform environment above a diffuse floor, once as a
// homogeneous medium and once as a grid medium of constant density 1 with the same
// sigma_t and albedo (a .vol file written here, loaded through the YAML loader). Delta
// tracking and ratio tracking must give the same expectation as the closed forms: the
// image mean and the 8x8-block means agree (Welch per block, Sidak over the blocks and
// the mean, family-wise 1%), 8 runs x 16 spp each. Planted defect, rejected by the same
// test: NEE without the shadow ray's transmittance (VolpathFault::nee_without_transmittance)
// on the grid scene only. Also: the grid scene runs delta tracking (counter), and a ramp
// grid renders without NaN.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <unistd.h>

#include "integrators/beam/beam_integrator.h"
#include "integrators/bre/bre_integrator.h"
#include "integrators/integrator.h"
#include "integrators/volpath/volpath_integrator.h"
#include "integrators/vpm/vpm_integrator.h"
#include "scene/loaders/loader.h"
#include "scene/media/density_grid.h"
#include "tests/integrators/grid_ball_support.h"
#include "tests/support/welch.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

constexpr int kBlock = 8, kRuns = 8, kSpp = 16;



using Render = std::function<integrators::RenderResult(const scene::Scene&, const integrators::RenderOptions&)>;

// kRuns renders (kSpp spp each, seeds seed0 + k) by `render`: their block statistics, and
// the sum of the counter `counter` (if given).
std::vector<std::vector<double>> runs_of(const scene::Scene& s, const Render& render, uint64_t seed0,
                                         const char* counter = nullptr, int64_t* count = nullptr) {
  std::vector<std::vector<double>> r;
  for (int k = 0; k < kRuns; ++k) {
    const integrators::RenderOptions opt = test::grid_render_options(kSpp, seed0 + uint64_t(k));
    const auto res = render(s, opt);
    if (count) *count += res.stats.get(counter);
    const auto b = test::image_blocks(res.layers[0].image, kBlock);
    if (r.empty()) r.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i) r[i].push_back(b[i]);
  }
  return r;
}

std::vector<std::vector<double>> runs(const scene::Scene& s, integrators::VolpathFault fault, uint64_t seed0,
                                      int64_t* grid_flights = nullptr) {
  integrators::VolpathSettings v;
  v.fault = fault;
  return runs_of(s, [&](const scene::Scene& sc, const integrators::RenderOptions& o) {
    return integrators::VolpathIntegrator(v).render(sc, o);
  }, seed0, "volpath.grid_flights", grid_flights);
}


}  // namespace

TEST_CASE("volpath: a constant grid medium renders as the homogeneous one", "[stat]") {
  const test::GridBallScenes scenes("volpath_grid");
  const scene::Scene &homogeneous = *scenes.homogeneous, &grid = *scenes.grid, &ramp = *scenes.ramp;
  REQUIRE(grid.media()[0].heterogeneous());
  const auto ref = runs(homogeneous, integrators::VolpathFault::none, 100);
  int64_t flights = 0;
  const auto a = runs(grid, integrators::VolpathFault::none, 200, &flights);
  const auto bad = runs(grid, integrators::VolpathFault::nee_without_transmittance, 300);
  const double ok_ratio = test::sidak_welch(a, ref, 0.01), bad_ratio = test::sidak_welch(bad, ref, 0.01);
  std::printf("[volpath grid] image mean %.4f vs homogeneous %.4f: worst |t|/crit %.2f (mean and %zu blocks); "
              "NEE without transmittance %.2f; delta-tracked flights %lld\n",
              test::moments(a[0]).mean, test::moments(ref[0]).mean, ok_ratio, a.size() - 1, bad_ratio,
              (long long)flights);
  CHECK(ok_ratio < 1.0);
  CHECK(bad_ratio > 1.0);
  CHECK(flights > 0);
  int64_t ramp_flights = 0;
  const auto r = runs(ramp, integrators::VolpathFault::none, 400, &ramp_flights);
  for (const auto& v : r)
    for (double x : v) CHECK(std::isfinite(x));
  CHECK(ramp_flights > 0);
  // volpath, path, bdpt, vpm and bre render grid media (bdpt: test_bdpt_grid.cpp; vpm, bre:
  // below); gvpm (homogeneous only) refuses them.
  integrators::Settings s;
  CHECK_THROWS_WITH(integrators::check_scene_support(*integrators::make_integrator("gvpm", s), grid),
                    Catch::Contains("homogeneous media only") && Catch::Contains("volpath"));
}

// vpm, bre (kernel 3d) and beam (Beam-Beam 3D) on the same pair of scenes: photons and
// beams by delta tracking, Tr along the camera segments from one ratio-tracking profile
// each (grid_tracking.h). The kernel
// estimates of both scenes have the same expectation (the photons' density and the camera
// side's Tr are estimated without bias), so the image mean and the 8x8 blocks agree by
// Welch tests (Sidak, family-wise 1%; 8 runs x 16 iterations). Planted defect: the gather
// point's Tr left out (VpmFault::no_transmittance, BreFault::no_transmittance,
// BeamFault::no_camera_transmittance) on the grid scene only -- rejected. The ramp grid
// renders finite.
TEST_CASE("vpm, bre and beam: a constant grid medium renders as the homogeneous one", "[stat]") {
  const test::GridBallScenes scenes("vpm_grid");
  for (const int kind : {0, 1, 2}) {
    const bool bre = kind == 1;
    auto render = [&](bool fault) -> Render {
      return [=](const scene::Scene& sc, const integrators::RenderOptions& o) {
        if (kind == 2) {
          integrators::BeamSettings b;
          b.photons = 2000;
          b.radius_scale = 0.01;
          if (fault) b.fault = integrators::BeamFault::no_camera_transmittance;
          return integrators::BeamIntegrator(b).render(sc, o);
        }
        if (bre) {
          integrators::BreSettings b;
          b.photons = 20000;
          b.radius_scale = 0.01;
          b.kernel_dim = 3;
          if (fault) b.fault = integrators::BreFault::no_transmittance;
          return integrators::BreIntegrator(b).render(sc, o);
        }
        integrators::VpmSettings v;
        v.photons = 20000;
        v.radius_scale = 0.01;
        v.distance_samples = 4;
        if (fault) v.fault = integrators::VpmFault::no_transmittance;
        return integrators::VpmIntegrator(v).render(sc, o);
      };
    };
    const char* name = kind == 2 ? "beam" : bre ? "bre" : "vpm";
    const std::string counter = std::string(name) + ".photon_grid_flights";
    int64_t flights = 0, none = 0;
    const auto ref = runs_of(*scenes.homogeneous, render(false), 500, counter.c_str(), &none);
    const auto a = runs_of(*scenes.grid, render(false), 600, counter.c_str(), &flights);
    const auto bad = runs_of(*scenes.grid, render(true), 700);
    const double ok_ratio = test::sidak_welch(a, ref, 0.01), bad_ratio = test::sidak_welch(bad, ref, 0.01);
    std::printf("[%s grid] image mean %.4f vs homogeneous %.4f: worst |t|/crit %.2f; Tr left out %.2f; "
                "delta-tracked photon flights %lld (homogeneous %lld)\n",
                name, test::moments(a[0]).mean, test::moments(ref[0]).mean, ok_ratio, bad_ratio, (long long)flights,
                (long long)none);
    CHECK(ok_ratio < 1.0);
    CHECK(bad_ratio > 1.0);
    CHECK(flights > 0);
    CHECK(none == 0);
    const auto r = runs_of(*scenes.ramp, render(false), 800);
    for (const auto& v : r)
      for (double x : v) CHECK(std::isfinite(x));
  }
}
