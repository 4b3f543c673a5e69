// G-VCM (`gvcm`, Sun et al. 2017):
//  * furnace (unit): in the closed diffuse sphere every shifted term -- connections, light
//    tracing, merges of case 1 (shared vertex) and case 2 (the merging shift at z_b) --
//    has an offset equal to its base up to float round-off (chord property,
//    tests/support/furnace_bound.h), so each sample's gradients sum to zero within the
//    sum of its terms' bounds; every Jacobian reported as 1 is rejected;
//  * consistency (stat): at a small radius the dx / dy block sums and the L2 mean agree
//    with PT and with BDPT on the glossy + glass box, and with PT on the caustic box
//    (SDS: merges through the photons' specular chains, case 2 walks); the gradient weight
//    without the passive strategies (w = the base's VCM weight) is rejected
//    (tests/integrators/gpt_unbiased_support.h: Welch t-tests, Sidak over blocks).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <limits>

#include "integrators/gvcm/gvcm_integrator.h"
#include "integrators/gvcm/gvcm_tracer.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/gpt_unbiased_support.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

struct FurnaceResult {
  double worst = 0;  // max over samples of sum |g| / (4 eps(d_min) sum of w f/p)
  int64_t samples = 0, pairs = 0, fallbacks = 0, case1 = 0, case2 = 0;
};

double segments_min(const pathspace::BidirVertex* v, int n) {
  double d = std::numeric_limits<double>::infinity();
  for (int k = 1; k < n; ++k) d = std::min(d, double((v[k].sp.p - v[k - 1].sp.p).norm()));
  return d;
}

FurnaceResult furnace(const scene::Scene& s, const integrators::GvcmSettings& settings) {
  const int res = s.camera().width(), depth = 6;
  integrators::VcmSettings vs;
  vs.mode = integrators::VcmMode::vcm;
  integrators::VcmIteration it;
  it.seed = 11;
  it.max_depth = depth;
  it.radius = 0.05f;
  it.light_tracing = false;
  it.mis.eta = float(kPiD * 0.05 * 0.05 * double(res * res));
  it.mis.adaptive_kernel = settings.adaptive_kernel;
  integrators::LightPathStore light;
  integrators::VcmLightCounters lc;
  REQUIRE(integrators::trace_light_paths(s, vs, it, int64_t(res) * res, 1, nullptr, light, lc));
  integrators::PhotonGrid grid;
  light.collect_photons(1);
  grid.build(light.photon_pos, it.radius);
  light.gather_photons(grid.order());
  const integrators::GvcmTracer tracer(s, settings, it, light, grid);
  integrators::GvcmScratch sc;
  integrators::GvcmCounters counters;
  gradients::GradientBuffers buf(res, res);
  core::Rng rng(3, 4);
  FurnaceResult out;
  for (int rep = 0; rep < 4; ++rep)
    for (int py = 0; py < res; ++py)
      for (int px = 0; px < res; ++px) {
        tracer.sample(px, py, rng, sc, buf, counters);
        if (sc.terms.empty()) continue;
        // d_min: the camera subpath's, the pixel's light path's and every merged photon's
        // light subpath's segments; offsets' new segments (reconnections, y_s -> z_b^off)
        // lie within a pixel's footprint and a kernel of a base segment: half of it.
        const pathspace::VcmPrefix* pre = nullptr;
        int nl = 0;
        const pathspace::BidirVertex* y = light.path(int64_t(py) * res + px, &pre, &nl);
        double d_min = std::min(segments_min(sc.camera.data(), int(sc.camera.size())), segments_min(y, nl));
        double sum_base = 0;
        for (const auto& t : sc.terms) {
          sum_base += t.w * double(t.value.maxCoeff());
          if (!t.merge) continue;
          const auto& ph = light.photons[t.photon];
          const pathspace::BidirVertex* yp = light.path(int64_t(ph.path), &pre, &nl);
          d_min = std::min(d_min, segments_min(yp, ph.depth + 1));
        }
        d_min *= 0.5;
        double sum_g = 0;
        for (const auto& a : sc.splats.adds)
          if (a.layer >= 2) sum_g += a.v.cwiseAbs().maxCoeff();
        ++out.samples;
        out.worst = std::max(out.worst, sum_g / (4.0 * furnace_roundoff_bound(d_min) * sum_base));
      }
  out.pairs = counters.pairs_shifted;
  out.fallbacks = counters.pairs_fallback;
  out.case1 = counters.merge_case1;
  out.case2 = counters.merge_case2_shifted;
  return out;
}

integrators::GvcmSettings defaults() {
  integrators::Settings raw;
  return integrators::GvcmSettings::read(raw);
}

integrators::GvcmSettings small_radius() {
  integrators::GvcmSettings g = defaults();
  g.radius_scale = 0.1f;
  return g;
}

Blocks gvcm_stats(const scene::Scene& s, const integrators::GvcmSettings& settings, int iterations, uint64_t seed0) {
  integrators::GvcmIntegrator in(settings, core::Json::object());
  return stats_of(s, in, true, iterations, seed0);
}

void print(const char* what, const Verdict& v, const Blocks& g, const Blocks& p, const char* ref = "PT") {
  std::printf("gvcm consistency [%s]: gradients worst |t|/crit %.2f (|t| %.2f, block %d), L2 mean %.5f vs %s %.5f "
              "(z %.2f, |t|/crit %.2f)%s\n",
              what, v.grad, v.zmax, v.worst_block, moments(g.mean).mean, ref, moments(p.mean).mean, v.zl2, v.l2,
              v.rejects() ? " -> rejected" : "");
}

}  // namespace

TEST_CASE("G-VCM furnace: every shifted term equals its base within the round-off bound; J = 1 is rejected",
          "[unit]") {
  // Without the adaptive kernel (merges after the first vertex keep the full radius, so
  // case 1 is exercised often); with it, below.
  const auto s = furnace_sphere(0.5f, 0.5f, 0.0f, 8);
  integrators::GvcmSettings settings = defaults();
  settings.adaptive_kernel = false;
  const FurnaceResult ok = furnace(*s, settings);
  settings.faults.jacobian = gradients::JacobianFault::unit;
  const FurnaceResult bad = furnace(*s, settings);
  std::printf("gvcm furnace: %lld samples, %lld shifted pairs (%lld merges case 1, %lld case 2), %lld fallbacks; worst "
              "sum |g| / bound %.3f (fault J = 1: %.3g)\n",
              (long long)ok.samples, (long long)ok.pairs, (long long)ok.case1, (long long)ok.case2,
              (long long)ok.fallbacks, ok.worst, bad.worst);
  REQUIRE(ok.pairs > 1000);
  REQUIRE(ok.case1 > 100);
  REQUIRE(ok.case2 > 100);
  CHECK(ok.fallbacks == 0);  // a closed diffuse sphere: every term shifts
  CHECK(ok.worst <= 1.0);
  CHECK(bad.worst > 1.0);
  // The adaptive kernel: past a diffuse vertex r^2 shrinks by 0.25^10, so case-1 merges
  // become rare; each shifted merge uses the base's kernel and the same photon.
  settings = defaults();
  const FurnaceResult adaptive = furnace(*s, settings);
  std::printf("gvcm furnace, adaptive kernel: %lld shifted pairs (%lld merges case 1, %lld case 2), %lld fallbacks; "
              "worst sum |g| / bound %.3f\n",
              (long long)adaptive.pairs, (long long)adaptive.case1, (long long)adaptive.case2,
              (long long)adaptive.fallbacks, adaptive.worst);
  REQUIRE(adaptive.case2 > 100);
  CHECK(adaptive.fallbacks == 0);
  CHECK(adaptive.worst <= 1.0);
}

TEST_CASE("G-VCM gradients and L2 mean agree with PT and BDPT at a small radius; an MIS defect is rejected", "[stat]") {
  const auto s = lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                     scene::ConductorFresnel{},
                                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                         scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx, nullptr, nullptr), kRes);
  const Blocks p = stats(*s, "path", 64, 2000);
  const int iters = 64;
  const Blocks g = gvcm_stats(*s, small_radius(), iters, 1000);
  const Verdict v = verdict(g, p);
  print("glossy + glass box", v, g, p);
  std::printf("gvcm consistency power (%d iterations x %d runs vs PT 64 spp): a gradient scale error >= %.1f%%, an L2 "
              "mean shift >= %.2f%%\n",
              iters, kRuns, 100 * v.grad_scale, 100 * v.l2_shift);
  CHECK_FALSE(v.rejects());
  const Blocks b = stats(*s, "bdpt", 64, 3000);
  const Verdict vb = verdict(g, b);
  print("glossy + glass box", vb, g, b, "BDPT");
  CHECK_FALSE(vb.rejects());
  integrators::GvcmSettings bad = small_radius();
  bad.faults.mis_without_offset = true;
  const Blocks gb = gvcm_stats(*s, bad, iters, 1000);
  const Verdict vf = verdict(gb, p);
  print("fault: gradient weight without the passive strategies", vf, gb, p);
  CHECK(vf.rejects());
}

TEST_CASE("G-VCM on the caustic box (SDS through merges, the photons' chains walked) agrees with PT; a walk Jacobian defect is rejected", "[stat]") {
  const auto s = caustic_box(kRes);
  const Blocks p = stats(*s, "path", 512, 2000);
  const int iters = 256;
  integrators::GvcmSettings settings = small_radius();
  const Blocks g = gvcm_stats(*s, settings, iters, 1200);
  const Verdict v = verdict(g, p);
  print("caustic box", v, g, p);
  std::printf("gvcm consistency power (caustic box, %d iterations): a gradient scale error >= %.1f%%, an L2 mean "
              "shift >= %.2f%%\n",
              iters, 100 * v.grad_scale, 100 * v.l2_shift);
  CHECK_FALSE(v.rejects());
  // The walked chains' factors reported as 1 (the camera side's |dw'_b/dw_b|, the light
  // side's area factor through the chain: light tracing and case-2 merges).
  settings.faults.jacobian = gradients::JacobianFault::unit_manifold;
  const Blocks gb = gvcm_stats(*s, settings, iters, 1200);
  const Verdict vb = verdict(gb, p);
  print("fault: walk Jacobian = 1", vb, gb, p);
  CHECK(vb.rejects());
}
