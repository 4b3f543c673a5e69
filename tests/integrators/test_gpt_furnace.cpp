// G-PT furnace and skip tests. In the closed diffuse sphere (albedo 0.5, emission 0.5,
// exact radiance 1) every concrete path has f/p = albedo^k Le whatever its geometry, and
// the reconnection shift preserves it exactly (chord property cos a cos b / d^2 = 1/4R^2),
// so every sampled gradient is zero up to float round-off (bound derived below, checked
// per sample and pixel pair) and both reconstructions equal 1 within the primal's noise
// (L1 up to its median bias, measured).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <limits>

#include "integrators/gpt/gpt_settings.h"
#include "integrators/gpt/gpt_tracer.h"
#include "integrators/integrator.h"
#include "pathspace/measure.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/gpt_unbiased_support.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
integrators::RenderResult render_gpt(const scene::Scene& s, int spp, uint64_t seed, int max_depth,
                                     const std::vector<std::pair<std::string, std::string>>& set = {}) {
  return test::render_with(s, "gpt", spp, seed, max_depth, set);
}
const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  FAIL("missing layer " << name);
  return r.layers[0].image;
}
}  // namespace

// The round-off bound of one sampled gradient in the furnace: tests/support/furnace_bound.h.
// As the symmetric MIS weights are <= 1, the gradient of every pixel pair of one sample
// satisfies |grad| <= eps(d_min) * S, S = sum over the sample's concrete paths of f(x)/p(x).
// (Before the vertex-anchored rays of pathspace/scatter.h the ray origin was pushed by
// ~2e-5 along the normal; that adds 2e-5 sin^2/(2R cos^2) relative per bounce -- well
// above this bound for all but near-normal bounces.)
TEST_CASE("G-PT furnace: every sampled gradient is zero within its round-off bound", "[stat]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, 16);
  const int res = 16, spp = 8;
  integrators::GptSettings settings;
  const integrators::GptTracer tracer(*s, settings, 100);
  core::Rng rng(7, 3);
  pathspace::PrimarySampleStream stream(rng);
  pathspace::Path base;
  gradients::ShiftResult shifted;
  integrators::GptCounters counters;
  double worst_ratio = 0, worst_rel = 0, worst_rel_dmin = 0, sum_abs = 0;
  int64_t pairs = 0, exactly_zero = 0;
  std::vector<double> ratios;
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int py = 0; py < res; ++py)
    for (int px = 0; px < res; ++px)
      for (int i = 0; i < spp; ++i) {
        stream.clear();
        tracer.builder().build(px, py, stream, base);
        // d_min over every segment of the base and of its four offsets, and S.
        double d_min = std::numeric_limits<double>::infinity();
        auto seg = [&](const Vec3& a, const Vec3& b) { d_min = std::min(d_min, double((a - b).norm())); };
        auto scan = [&](const pathspace::Path& p, int n, const gradients::ShiftResult* r) {
          for (int k = 1; k < n; ++k) {
            if (k + 1 < n && p[k + 1].is_surface()) seg(p[k].p(), p[k + 1].p());
            const auto& l = p.nee[size_t(k)];
            if (l.valid && (!r || r->nee_ok(k)) && std::isfinite(l.dist)) seg(p[k].p(), l.p);
          }
        };
        scan(base, base.size(), nullptr);
        for (int nb = 0; nb < 4; ++nb) {
          const int qx = px + kDx[nb], qy = py + kDy[nb];
          if (qx < 0 || qy < 0 || qx >= res || qy >= res) continue;
          tracer.shift().shift(base, Vec2(float(kDx[nb]), float(kDy[nb])), shifted);
          scan(shifted.path, shifted.alive, &shifted);
        }
        double S = 0;
        for (int k = 1; k < base.size(); ++k) {
          S += double(pathspace::nee_estimate(base, k).maxCoeff());
          if (k >= 2) S += double(pathspace::emission_estimate(base, k).maxCoeff());
        }
        const double eps = test::furnace_roundoff_bound(d_min);
        // The same sample through the integrator's tracer (replayed primary samples).
        stream.rewind();
        gradients::GradientBuffers buf(res, res);
        tracer.sample(px, py, stream, buf, counters);
        for (int nb = 0; nb < 4; ++nb) {
          const int qx = px + kDx[nb], qy = py + kDy[nb];
          if (qx < 0 || qy < 0 || qx >= res || qy >= res) continue;
          const Rgbd g = kDx[nb] == 1 ? buf.dx_sum(px, py)
                       : kDx[nb] == -1 ? buf.dx_sum(qx, qy)
                       : kDy[nb] == 1 ? buf.dy_sum(px, py)
                                      : buf.dy_sum(qx, qy);
          const double a = g.abs().maxCoeff();
          ++pairs;
          exactly_zero += a == 0.0;
          sum_abs += a;
          const double ratio = S > 0 ? a / (eps * S) : (a > 0 ? std::numeric_limits<double>::infinity() : 0.0);
          ratios.push_back(ratio);
          worst_ratio = std::max(worst_ratio, ratio);
          if (S > 0 && a / S > worst_rel) worst_rel = a / S, worst_rel_dmin = d_min;
        }
      }
  std::sort(ratios.begin(), ratios.end());
  const auto quant = [&](double f) { return ratios[std::min(ratios.size() - 1, size_t(f * double(ratios.size())))]; };
  std::printf("gpt furnace per sample: %lld pair gradients, %lld exactly 0, mean |grad| %.2e; |grad|/S worst %.2e "
              "(d_min %.3f); |grad|/(eps S) median %.2e p99 %.2e max %.2e\n",
              (long long)pairs, (long long)exactly_zero, sum_abs / double(pairs), worst_rel, worst_rel_dmin,
              quant(0.5), quant(0.99), worst_ratio);
  // Every shift succeeds in the furnace (otherwise a sample would carry -w f(x) alone).
  REQUIRE(counters.shifts > 0);
  REQUIRE(counters.shifts_full == counters.shifts);
  for (int c = 1; c < gradients::kShiftStatusCount; ++c) REQUIRE(counters.nee_fail[size_t(c)] == 0);
  REQUIRE(counters.nan_dropped == 0);
  REQUIRE(pairs == int64_t(spp) * 4 * res * (res - 1));
  REQUIRE(worst_ratio <= 1.0);
}

TEST_CASE("G-PT furnace: L2 and L1 reconstructions equal 1 (L1 up to its median bias)", "[render]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, 16);
  const auto r = render_gpt(*s, 8, 1, 100);
  REQUIRE(r.stats.get("gpt.nan_dropped") == 0);
  REQUIRE(r.stats.get("gpt.shift.complete") == r.stats.get("gpt.shift.attempted"));
  const core::Image& primal = layer(r, "primal");
  std::vector<double> v;
  double m = 0, m2 = 0;
  for (const auto& p : primal.pixels()) {
    v.push_back(double(p[0]));
    m += double(p[0]), m2 += double(p[0]) * double(p[0]);
  }
  const double n = double(v.size());
  m /= n;
  const double sd = std::sqrt((m2 / n - m * m) * n / (n - 1)), se = sd / std::sqrt(n);
  std::sort(v.begin(), v.end());
  const double median = 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  const double se_median = 1.2533 * se;  // asymptotic SE of a sample median (normal data)
  std::printf("gpt furnace: primal mean %.5f (SE %.5f, pixel sd %.4f), primal median %.5f (SE %.5f)\n", m, se, sd,
              median, se_median);
  REQUIRE(se > 0);
  REQUIRE(std::abs(m - 1.0) < 3 * se);  // the primal is unbiased (pixels are independent)

  // L2 with zero gradients: (H^T H + a^2) I = a^2 I_g + H^T b, and 1^T H^T = 0, so the
  // image mean is the primal's exactly (up to float storage), whatever the (round-off)
  // gradients are; each pixel is a convex combination of primal pixels (a low-pass
  // filter), so its spread cannot exceed the primal's.
  const core::Image& l2 = layer(r, "recon_l2");
  double l2_mean = l2.mean()[0], l2_worst = 0, primal_worst = 0;
  for (const auto& p : l2.pixels()) l2_worst = std::max(l2_worst, std::abs(double(p[0]) - 1.0));
  for (double x : v) primal_worst = std::max(primal_worst, std::abs(x - 1.0));
  // L1 (group-L1 IRLS, reconstruct/solve.h: robust but biased): with zero gradient rows
  // weighted 1 and primal rows weighted alpha = 0.2, the minimizer of
  // sum |grad I| + alpha sum |I - I_g| over a 16x16 image is (near) constant, and the
  // constant minimizing sum |c - I_g| is the MEDIAN of the primal. Its bias is therefore
  // E[median] - E[mean] of the primal's pixel distribution (skewed to the right by
  // long paths: median < mean), which is measured here, not banded.
  const core::Image& l1 = layer(r, "recon_l1");
  const double l1_mean = l1.mean()[0];
  double l1_spread = 0;
  for (const auto& p : l1.pixels()) l1_spread = std::max(l1_spread, std::abs(double(p[0]) - l1_mean));
  std::printf("gpt furnace: L2 mean %.6f (|L2 - primal mean| %.1e), worst |L2 - 1| %.4f <= primal's %.4f; "
              "L1 mean %.5f, spread %.1e, L1 - primal median %.1e, L1 bias vs 1 %.5f = %.1f primal SE\n",
              l2_mean, std::abs(l2_mean - m), l2_worst, primal_worst, l1_mean, l1_spread, l1_mean - median,
              l1_mean - 1.0, (l1_mean - 1.0) / se);
  REQUIRE(std::abs(l2_mean - m) < 1e-5);
  REQUIRE(std::abs(l2_mean - 1.0) < 3 * se);
  REQUIRE(l2_worst <= primal_worst);
  REQUIRE(std::abs(l1_mean - median) < 3 * se_median);
  REQUIRE(l1_spread < sd);  // (near) constant, unlike the primal
}

TEST_CASE("G-PT skips the half-vector machinery on scenes without glossy or specular BSDFs", "[render]") {
  const auto diffuse = test::lit_box(nullptr, nullptr, 8);
  REQUIRE_FALSE(diffuse->caps().has_glossy);
  REQUIRE_FALSE(diffuse->caps().has_specular);
  const auto r = render_gpt(*diffuse, 4, 2, 6);
  REQUIRE(r.stats.get("gpt.step.reconnect.succeeded") > 500);
  REQUIRE(r.stats.get("gpt.step.half_vector.attempted") == 0);
  REQUIRE(r.stats.get("gpt.step.nee_half_vector.attempted") == 0);
  // The same counters do move on a scene that needs them (so the assertion can fail).
  const auto mirror = test::lit_box(scene::make_mirror(scene::constant_texture(Rgb::Constant(0.9f))),
                                    scene::make_two_sided(scene::make_conductor(
                                        0.05f, 0.05f, scene::MicrofacetType::ggx, scene::ConductorFresnel{})),
                                    8);
  const auto r2 = render_gpt(*mirror, 4, 2, 6, {{"shift_threshold", "0.1"}});
  REQUIRE(r2.stats.get("gpt.step.half_vector.attempted") > 0);
  REQUIRE(r2.stats.get("gpt.step.dirac.attempted") > 0);
}
