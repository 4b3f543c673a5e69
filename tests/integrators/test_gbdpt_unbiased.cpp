// Unbiasedness of G-BDPT against the reference PT (and BDPT) on the small lit box with a glossy
// conductor sphere and a glass sphere (Dirac copies through glass, reconnections at the
// glossy and diffuse vertices, light tracing): block sums of the dx / dy layers equal
// block sums of differences of PT's pixel expectations, and the mean of the L2
// reconstruction equals PT's image mean (Welch t-tests over independent renders, fixed
// seeds, Sidak-corrected over blocks; thresholds from the estimators' sample variances,
// gpt_unbiased_support.h). The same test must reject the real estimator run with a real
// defect (GbdptSettings::faults, C++ only).
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/gbdpt/gbdpt_tracer.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/gpt_unbiased_support.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {
void print(const char* what, const Verdict& v, const Blocks& g, const Blocks& p, const char* ref = "PT") {
  std::printf("gbdpt unbiasedness [%s]: gradients worst |t|/crit %.2f (|t| %.2f, block %d), L2 mean %.5f vs %s "
              "%.5f (z %.2f, |t|/crit %.2f)%s\n",
              what, v.grad, v.zmax, v.worst_block, moments(g.mean).mean, ref, moments(p.mean).mean, v.zl2, v.l2,
              v.rejects() ? " -> rejected" : "");
}

std::unique_ptr<scene::Scene> glossy_glass_box() {
  return lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                             scene::ConductorFresnel{},
                                                             scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                 scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx, nullptr, nullptr), kRes);
}

// One G-BDPT render through GbdptTracer with explicit settings (render_frame).
GptFrame render_gbdpt_tracer(const scene::Scene& s, const integrators::GbdptSettings& settings, int spp,
                             uint64_t seed, int max_depth, integrators::GbdptCounters& counters) {
  const integrators::GbdptTracer tracer(s, settings, max_depth);
  integrators::GbdptScratch scratch;
  return render_frame(s, spp, seed, settings.alpha,
                      [&](int x, int y, core::Rng& rng, gradients::GradientBuffers& buf) {
                        tracer.sample(x, y, rng, scratch, buf, counters);
                      });
}

Blocks gbdpt_tracer_stats(const scene::Scene& s, const integrators::GbdptSettings& settings, int spp,
                          uint64_t seed0, integrators::GbdptCounters* counters = nullptr) {
  integrators::GbdptCounters local;
  return frame_stats(seed0, [&](uint64_t seed) {
    return render_gbdpt_tracer(s, settings, spp, seed, 5, counters ? *counters : local);
  });
}
}  // namespace

TEST_CASE("G-BDPT gradients and L2 mean agree with PT in expectation; Jacobian and MIS defects are rejected",
          "[stat]") {
  const auto s = glossy_glass_box();
  const Blocks p = stats(*s, "path", 64, 2000);
  // The integrator (--integrator gbdpt) ...
  const Blocks g = stats(*s, "gbdpt", 16, 1000);
  const Verdict v = verdict(g, p);
  print("integrator", v, g, p);
  CHECK_FALSE(v.rejects());
  // ... and against BDPT (the primal's own estimator family: the same strategies).
  const Blocks b = stats(*s, "bdpt", 64, 3000);
  const Verdict v_bdpt = verdict(g, b);
  print("integrator", v_bdpt, g, b, "BDPT");
  CHECK_FALSE(v_bdpt.rejects());
  // ... and its tracer with explicit settings, the harness the defects below run through.
  integrators::Settings raw;
  const integrators::GbdptSettings settings = integrators::GbdptSettings::read(raw);
  const Blocks gt = gbdpt_tracer_stats(*s, settings, 16, 1100);
  const Verdict vt = verdict(gt, p);
  print("tracer, no fault", vt, gt, p);
  std::printf("gbdpt unbiasedness power (16 spp x %d runs vs PT 64 spp): a gradient scale error >= %.1f%% "
              "(90%%: %.1f%%), an L2 mean shift >= %.2f%% (90%%: %.2f%%)\n",
              kRuns, 100 * vt.grad_scale, 100 * vt.grad_scale90, 100 * vt.l2_shift, 100 * vt.l2_shift90);
  CHECK_FALSE(vt.rejects());

  // (a) Every shift Jacobian reported as 1 (the reconnection's solid-angle factor and the
  // light-tracing offset's area factor p_cam(x_1)/p_cam(y_1)): offsets lose their
  // change of measure.
  {
    integrators::GbdptSettings bad = settings;
    bad.faults.jacobian = gradients::JacobianFault::unit;
    const Blocks gb = gbdpt_tracer_stats(*s, bad, 16, 1100);
    const Verdict vb = verdict(gb, p);
    print("fault: Jacobian = 1", vb, gb, p);
    CHECK(vb.rejects());
  }
  // (b) The gradient weight normalised over the base pixel's strategies only (the
  // offset's p_r(T x)|T'| left out of Manzi 2015's Eq. 6): a pair's weights sum to ~2.
  {
    integrators::GbdptSettings bad = settings;
    bad.faults.mis_without_offset = true;
    const Blocks gb = gbdpt_tracer_stats(*s, bad, 16, 1100);
    const Verdict vb = verdict(gb, p);
    print("fault: MIS weight without the offset's strategies", vb, gb, p);
    CHECK(vb.rejects());
  }
}

TEST_CASE("G-BDPT through specular chains (manifold walks b..c) agrees with PT; a walk Jacobian defect is rejected",
          "[stat]") {
  // The caustic box: the floor is lit only through the glass sphere (L S+ D), so every
  // shifted pair there has a specular chain after b = the floor vertex, walked pinned at
  // its end c (the light) to the offset's b: camera strategies (s = 0) and light tracing
  // (gradients/bidir_chain.h).
  const auto s = caustic_box(kRes);
  const Blocks p = stats(*s, "path", 512, 2000);
  integrators::Settings raw;
  const integrators::GbdptSettings settings = integrators::GbdptSettings::read(raw);
  integrators::GbdptCounters counters;
  const Blocks g = gbdpt_tracer_stats(*s, settings, 64, 1200, &counters);
  const Verdict v = verdict(g, p);
  print("specular chains", v, g, p);
  std::printf("gbdpt chains: %lld camera shifts (%lld rejoined), %lld light-tracing shifts (%lld succeeded); %lld walks "
              "(%lld converged), %lld + %lld chains not walkable; power: gradient scale error >= %.1f%%, L2 mean shift "
              ">= %.2f%%\n",
              (long long)counters.camera_shifts, (long long)counters.camera_rejoined, (long long)counters.light_shifts,
              (long long)counters.light_shifted, (long long)counters.walks.attempted,
              (long long)counters.walks.converged, (long long)counters.camera_chain, (long long)counters.light_chain,
              100 * v.grad_scale, 100 * v.l2_shift);
  REQUIRE(counters.light_shifted > counters.light_shifts / 10);  // the chains are walked
  CHECK_FALSE(v.rejects());
  // The walked chains' factors (|d w'_b / d w_b| on the camera side, the area factor
  // through the chain for light tracing) reported as 1.
  integrators::GbdptSettings bad = settings;
  bad.faults.jacobian = gradients::JacobianFault::unit_manifold;
  const Blocks gb = gbdpt_tracer_stats(*s, bad, 64, 1200);
  const Verdict vb = verdict(gb, p);
  print("fault: walk Jacobian = 1", vb, gb, p);
  CHECK(vb.rejects());
}
