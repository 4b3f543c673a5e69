// G-PM (`gpm`, gradient-domain photon mapping as Sun et al. 2017 implement it):
//  * furnace (unit): in the closed diffuse sphere every merge's offset (the photon's light
//    subpath reconnected at z_b^off, Eq. 18) equals its base merge up to float round-off
//    (chord property, tests/support/furnace_bound.h), so every sampled gradient is zero
//    within its per-sample bound; the merging shift with its light-side area factor
//    reported as 1 is rejected;
//  * consistency (stat): at a small kernel (radius_scale 0.1, shrinking with alpha 0.9)
//    block sums of the dx / dy layers and the L2 mean agree with PT on the glossy + glass
//    box and on the caustic box (every floor path L S+ D: the photon's specular chain is
//    walked to z_b^off, Eq. 19-20); the area-factor defect and the gradient weight
//    without the passive strategy (w = 1 instead of 1 / (1 + R^2)) are rejected there
//    (tests/integrators/gpt_unbiased_support.h: Welch t-tests, Sidak over blocks).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <limits>

#include "integrators/gpm/gpm_integrator.h"
#include "integrators/gpm/gpm_tracer.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/gpt_unbiased_support.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

struct FurnaceResult {
  double worst = 0;  // max over shifted pairs of |g| / (base * eps(d_min))
  int64_t pairs = 0, fallbacks = 0;
};

// One iteration of G-PM's light pass and grid, then one camera sample per inner pixel;
// every gradient the tracer splats is compared with its base merge.
FurnaceResult furnace(const scene::Scene& s, const integrators::GpmSettings& settings) {
  const int res = s.camera().width(), depth = 6;
  integrators::VcmSettings vs;
  vs.mode = integrators::VcmMode::ppm;
  integrators::VcmIteration it;
  it.seed = 11;
  it.max_depth = depth;
  it.radius = 0.05f;
  integrators::LightPathStore light;
  integrators::VcmLightCounters lc;
  // 64 light paths per pixel (N = 64 res^2): enough photons in every kernel.
  REQUIRE(integrators::trace_light_paths(s, vs, it, int64_t(64) * res * res, 1, nullptr, light, lc));
  integrators::PhotonGrid grid;
  light.collect_photons(1);
  grid.build(light.photon_pos, it.radius);
  light.gather_photons(grid.order());
  const integrators::GpmTracer tracer(s, settings, depth, 1.0, light, grid);
  integrators::GpmScratch sc;
  integrators::GpmCounters counters;
  gradients::GradientBuffers buf(res, res);
  core::Rng rng(3, 4);
  FurnaceResult out;
  for (int py = 1; py + 1 < res; ++py)
    for (int px = 1; px + 1 < res; ++px) {
      tracer.sample(px, py, rng, sc, buf, counters);
      if (sc.terms.empty()) continue;
      const int nt = int(sc.terms.size());
      // d_min: the camera prefix's and the photons' light subpaths' segments; the offset's
      // segment y_s -> z_b^off is the base's y_s -> photon within a kernel and a pixel's
      // footprint, taken as half of it (conservative).
      double d_min = std::numeric_limits<double>::infinity();
      for (size_t k = 1; k < sc.camera.size(); ++k)
        d_min = std::min(d_min, double((sc.camera[k].sp.p - sc.camera[k - 1].sp.p).norm()));
      for (const auto& t : sc.terms) {
        const auto& ph = light.photons[t.photon];
        const pathspace::VcmPrefix* pre = nullptr;
        int len = 0;
        const pathspace::BidirVertex* y = light.path(int64_t(ph.path), &pre, &len);
        for (int k = 1; k < ph.depth; ++k) d_min = std::min(d_min, double((y[k].sp.p - y[k - 1].sp.p).norm()));
        d_min = std::min(d_min, 0.5 * double((y[ph.depth].sp.p - y[ph.depth - 1].sp.p).norm()));
      }
      const double eps = furnace_roundoff_bound(d_min);
      int g = 0;
      for (const auto& a : sc.splats.adds) {
        if (a.layer < 2) continue;
        const double base = double(sc.terms[size_t(g % nt)].value.maxCoeff());
        const double rel = double(a.v.cwiseAbs().maxCoeff()) / base;
        ++g;
        if (rel >= 0.999) {  // -base: the T_0 fallback
          ++out.fallbacks;
          continue;
        }
        ++out.pairs;
        out.worst = std::max(out.worst, rel / eps);
      }
      REQUIRE(g == 4 * nt);
    }
  return out;
}

integrators::GpmSettings small_kernel() {
  integrators::Settings raw;
  integrators::GpmSettings g = integrators::GpmSettings::read(raw);
  g.radius_scale = 0.1f;
  return g;
}

Blocks gpm_stats(const scene::Scene& s, const integrators::GpmSettings& settings, int iterations, uint64_t seed0) {
  integrators::GpmIntegrator in(settings, core::Json::object());
  return stats_of(s, in, true, iterations, seed0);
}

void print(const char* what, const Verdict& v, const Blocks& g, const Blocks& p) {
  std::printf("gpm consistency [%s]: gradients worst |t|/crit %.2f (|t| %.2f, block %d), L2 mean %.5f vs PT %.5f "
              "(z %.2f, |t|/crit %.2f)%s\n",
              what, v.grad, v.zmax, v.worst_block, moments(g.mean).mean, moments(p.mean).mean, v.zl2, v.l2,
              v.rejects() ? " -> rejected" : "");
}

}  // namespace

TEST_CASE("G-PM furnace: every merge's offset equals its base within the round-off bound; area factor 1 is rejected",
          "[unit]") {
  const auto s = furnace_sphere(0.5f, 0.5f, 0.0f, 8);
  integrators::Settings raw;
  integrators::GpmSettings settings = integrators::GpmSettings::read(raw);
  const FurnaceResult ok = furnace(*s, settings);
  settings.faults.unit_area_ratio = true;
  const FurnaceResult bad = furnace(*s, settings);
  std::printf("gpm furnace: %lld shifted merges, %lld fallbacks; worst |g| / (base eps): %.3f (fault: area factor 1: "
              "%.3g)\n",
              (long long)ok.pairs, (long long)ok.fallbacks, ok.worst, bad.worst);
  REQUIRE(ok.pairs > 1000);
  CHECK(ok.fallbacks == 0);  // a closed diffuse sphere: every merge shifts
  CHECK(ok.worst <= 1.0);
  CHECK(bad.worst > 1.0);
}

TEST_CASE("G-PM gradients and L2 mean agree with PT at a small kernel; area-factor and MIS defects are rejected",
          "[stat]") {
  const auto s = lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                     scene::ConductorFresnel{},
                                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                         scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx, nullptr, nullptr), kRes);
  const Blocks p = stats(*s, "path", 64, 2000);
  const integrators::GpmSettings settings = small_kernel();
  const int iters = 512;
  const Blocks g = gpm_stats(*s, settings, iters, 1000);
  const Verdict v = verdict(g, p);
  print("glossy + glass box", v, g, p);
  std::printf("gpm consistency power (%d iterations x %d runs vs PT 64 spp): a gradient scale error >= %.1f%%, an L2 "
              "mean shift >= %.2f%%\n",
              iters, kRuns, 100 * v.grad_scale, 100 * v.l2_shift);
  CHECK_FALSE(v.rejects());
  {
    integrators::GpmSettings bad = settings;
    bad.faults.mis_without_offset = true;
    const Blocks gb = gpm_stats(*s, bad, iters, 1000);
    const Verdict vb = verdict(gb, p);
    print("fault: gradient weight without the passive strategy", vb, gb, p);
    CHECK(vb.rejects());
  }
  {
    integrators::GpmSettings bad = settings;
    bad.faults.unit_area_ratio = true;
    const Blocks gb = gpm_stats(*s, bad, iters, 1000);
    const Verdict vb = verdict(gb, p);
    print("fault: area factor 1", vb, gb, p);
    CHECK(vb.rejects());
  }
}

TEST_CASE("G-PM through the photons' specular chains (the caustic box) agrees with PT", "[stat]") {
  const auto s = caustic_box(kRes);
  const Blocks p = stats(*s, "path", 512, 2000);
  const Blocks g = gpm_stats(*s, small_kernel(), 256, 1200);
  const Verdict v = verdict(g, p);
  print("caustic box", v, g, p);
  std::printf("gpm consistency power (caustic box, 256 iterations): a gradient scale error >= %.1f%%, an L2 mean shift "
              ">= %.2f%%\n",
              100 * v.grad_scale, 100 * v.l2_shift);
  CHECK_FALSE(v.rejects());
}
