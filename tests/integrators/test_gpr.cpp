// Gradient-domain path reusing (`gpr`, Bauszat et al. 2017, Sec. 3.2-3.3, Eq. 8):
//  (1) [stat] every gradient's expectation equals PT's pixel difference and the L2
//      reconstruction's image mean equals PT's: Welch t-tests over independent renders
//      (fixed seeds; thresholds from the run-to-run variances), (a) the image mean
//      (L2 vs PT) at 1%, (b) the 15 column sums of dx and the 15 row sums of dy (Sidak, 1%
//      family-wise), (c) every one of the 480 pixel pairs on its own (Sidak, 1%). Jittered
//      tiles T = 6 on a glossy box (alpha 0.2, reconnected) and a box with a glossy sphere
//      below the shift threshold (half-vector copies); and fixed tiles T = 4 (no jitter),
//      whose borders lie between columns/rows 3|4, 7|8, 11|12, so three column and three
//      row sums are pairs across tile borders only (reported apart). Rejected defects:
//      tiles without the one-pixel border (GprFaults::no_border: the border pairs get no
//      estimate), every reuse Jacobian forced to 1.
//  (2) [stat] the proportional Russian roulette keeps gpr unbiased with base paths of zero
//      contribution whose shifted paths carry light: a diffuse sphere with a black/white
//      checkerboard albedo (cells about a pixel) under an environment; a base starting on
//      a black cell has value 0 (q = q_min), its shifts to white cells do not. The
//      constructed case is asserted on sampled tiles (such bases exist, with q = q_min),
//      then the test of (1) passes with q_min = 0.1 and rejects q without the floor
//      (GprFaults::rr_without_floor: those fans are never reused). It found a defect of
//      the shared MIS densities (gradients/pair_terms.cpp): a pixel whose walk stops at a
//      vertex of black f (path_builder.cpp) was still counted as a sampler of the paths
//      through it, so gpr (and pr) were 16% low here with or without the roulette
//      (|t|/crit 7.6-8.4); fixed there.
//  (3) [unit] zero-gradient furnace: in the closed diffuse sphere every tile's gradient
//      of every inner pair is zero within the float round-off bound of its fans
//      (tests/support/furnace_bound.h); rejects the reuse Jacobians forced to 1.
// Directly seen emitters are hidden on both sides (gpr keeps them in its direct layer,
// never shifted), so the tests look at what the reuse estimates.
#include <catch2/catch.hpp>
#include <cstdio>
#include <limits>
#include <memory>

#include "integrators/gpr/gpr_integrator.h"
#include "integrators/gpr/gpr_tracer.h"
#include "integrators/integrator.h"
#include "pathspace/measure.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/bsdf/texture.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/quiet_options.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;
using namespace dp::integrators;

namespace {
constexpr int kRes = 16, kRuns = 12, kDepth = 5;
constexpr int kPtSpp = 64, kGprSpp = 16;
constexpr int kLines = 2 * (kRes - 1), kPairs = 2 * kRes * (kRes - 1);
// [statistic][run]: 0 = image mean; 1..kLines = column sums of dx (x = 0..14), then row
// sums of dy (y = 0..14); then every pair (dx row-major, then dy row-major).
using Runs = std::vector<std::vector<double>>;

const core::Image& layer(const RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  FAIL("missing layer " << name);
  return r.layers[0].image;
}

// One run: `mean_of`'s mean, and the forward differences, from dx / dy (gpr) or from the
// image's pixel differences (PT: dx = null).
void add_run(Runs& out, const core::Image& mean_of, const core::Image& img, const core::Image* dx,
             const core::Image* dy) {
  out.resize(size_t(1 + kLines + kPairs));
  out[0].push_back(double(mean_of.mean().sum()));
  auto px = [&](int x, int y) { return double(img(x, y).sum()); };
  auto gx = [&](int x, int y) { return dx ? double((*dx)(x, y).sum()) : px(x + 1, y) - px(x, y); };
  auto gy = [&](int x, int y) { return dy ? double((*dy)(x, y).sum()) : px(x, y + 1) - px(x, y); };
  size_t pair = 1 + kLines;
  for (int x = 0; x + 1 < kRes; ++x) {
    double s = 0;
    for (int y = 0; y < kRes; ++y) s += gx(x, y);
    out[size_t(1 + x)].push_back(s);
  }
  for (int y = 0; y + 1 < kRes; ++y) {
    double s = 0;
    for (int x = 0; x < kRes; ++x) s += gy(x, y);
    out[size_t(kRes + y)].push_back(s);
  }
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x + 1 < kRes; ++x) out[pair++].push_back(gx(x, y));
  for (int y = 0; y + 1 < kRes; ++y)
    for (int x = 0; x < kRes; ++x) out[pair++].push_back(gy(x, y));
}

GprSettings gpr_settings(int tile, bool jitter) {
  Settings s;
  s.set("tile", std::to_string(tile));
  s.set("hide_emitters", "true");
  s.set("jitter", jitter ? "true" : "false");
  return GprSettings::read(s);
}

Runs gpr_runs(const scene::Scene& s, const GprSettings& settings, uint64_t seed0) {
  GprIntegrator in(settings, core::Json::object());
  Runs out;
  for (int r = 0; r < kRuns; ++r) {
    const RenderResult res = in.render(s, test::quiet_options(kGprSpp, seed0 + uint64_t(r), kDepth));
    add_run(out, layer(res, "recon_l2"), layer(res, "primal"), &layer(res, "dx"), &layer(res, "dy"));
  }
  return out;
}

Runs pt_runs(const scene::Scene& s, uint64_t seed0) {
  Settings settings;
  settings.set("hide_emitters", "true");
  auto pt = make_integrator("path", settings);
  Runs out;
  for (int r = 0; r < kRuns; ++r) {
    const RenderResult res = pt->render(s, test::quiet_options(kPtSpp, seed0 + uint64_t(r), kDepth));
    add_run(out, res.layers[0].image, res.layers[0].image, nullptr, nullptr);
  }
  return out;
}

Runs slice(const Runs& r, size_t from, size_t to) { return Runs(r.begin() + long(from), r.begin() + long(to)); }

struct Verdict {
  double mean = 0, lines = 0, pairs = 0, border = 0;  // |t|/crit: >= 1 rejects
  bool rejects() const { return mean >= 1.0 || lines >= 1.0 || pairs >= 1.0; }
};

// `border`: the line statistics (1-based indices) of pairs across fixed tile borders.
Verdict verdict(const char* what, const Runs& g, const Runs& p, const std::vector<size_t>& border = {}) {
  Verdict v;
  v.mean = test::welch_ratio(test::moments(g[0]), test::moments(p[0]), 0.01);
  v.lines = test::sidak_welch(slice(g, 1, 1 + kLines), slice(p, 1, 1 + kLines), 0.01);
  v.pairs = test::sidak_welch(slice(g, 1 + kLines, g.size()), slice(p, 1 + kLines, p.size()), 0.01);
  const double sidak = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(kLines));
  for (size_t i : border)
    v.border = std::max(v.border, test::welch_ratio(test::moments(g[i]), test::moments(p[i]), sidak));
  std::printf("gpr vs PT [%s]: L2 mean %.5f vs %.5f (|t|/crit %.2f), lines %.2f, pairs %.2f, border lines %.2f%s\n",
              what, test::moments(g[0]).mean, test::moments(p[0]).mean, v.mean, v.lines, v.pairs, v.border,
              v.rejects() ? " -> rejected" : "");
  return v;
}

scene::BsdfPtr conductor(float alpha) {
  return scene::make_two_sided(scene::make_conductor(alpha, alpha, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
}

// A diffuse sphere whose albedo alternates black / white in cells of about a pixel.
std::unique_ptr<scene::Scene> checker_env() {
  auto checker = std::make_shared<scene::CheckerboardTexture>(Rgb::Zero(), Rgb::Constant(0.8f), Vec2(40.0f, 20.0f));
  return test::env_glossy(scene::make_diffuse(checker), kRes);
}
}  // namespace

TEST_CASE("gpr: gradients (tile borders included) and the L2 mean agree with PT", "[stat]") {
  {
    const auto s = test::lit_box(conductor(0.2f), nullptr, kRes);
    const Runs pt = pt_runs(*s, 2000);
    CHECK_FALSE(verdict("glossy box alpha 0.2, T 6 jittered", gpr_runs(*s, gpr_settings(6, true), 1000), pt).rejects());
    // Fixed tiles of 4: the column sums x = 3, 7, 11 and row sums y = 3, 7, 11 are pairs
    // across tile borders only (covered by the one-pixel border of Sec. 3.2).
    const std::vector<size_t> border = {1 + 3, 1 + 7, 1 + 11, kRes + 3, kRes + 7, kRes + 11};
    const GprSettings fixed = gpr_settings(4, false);
    const Verdict vf = verdict("glossy box alpha 0.2, T 4 fixed", gpr_runs(*s, fixed, 1100), pt, border);
    CHECK_FALSE(vf.rejects());
    CHECK(vf.border < 1.0);
    // (a) Tiles without the border: the pairs across tile borders get no estimate.
    GprSettings bad = fixed;
    bad.faults.no_border = true;
    CHECK(verdict("T 4 fixed, fault: no border", gpr_runs(*s, bad, 1100), pt, border).border >= 1.0);
    // (b) Every reuse Jacobian |R'| reported as 1 (Eq. 8 without |R'_k->i|).
    bad = gpr_settings(6, true);
    bad.reuse.faults.jacobian = gradients::JacobianFault::unit;
    CHECK(verdict("T 6, fault: Jacobian = 1", gpr_runs(*s, bad, 1000), pt).rejects());
  }
  {
    // alpha 0.03 is below the 0.05 shift threshold: the sphere is copied by half vectors.
    const auto s = test::lit_box(conductor(0.03f), nullptr, kRes);
    CHECK_FALSE(verdict("glossy alpha 0.03, T 6 jittered", gpr_runs(*s, gpr_settings(6, true), 1200), pt_runs(*s, 2200))
                    .rejects());
  }
}

TEST_CASE("gpr: the base-path Russian roulette is unbiased with zero-valued bases whose shifts carry light", "[stat]") {
  const auto s = checker_env();
  const GprSettings settings = gpr_settings(6, true);
  // The constructed case exists: bases of value 0 (q = q_min) whose reuse in another
  // pixel of the tile is nonzero.
  {
    const GprTracer tracer(*s, settings, kDepth);
    std::vector<pathspace::Path> bases;
    ReuseFan fan;
    PrCounters counters;
    gradients::PairTerms scratch;
    int64_t zero_bases = 0, zero_with_light = 0;
    for (int t = 0; t < 20; ++t) {
      const ReuseTile tile{4 + t % 3, 4 + t % 2, 11 + t % 3, 11 + t % 2};
      core::Rng rng(91, uint64_t(t));
      tracer.reuse().build_bases(tile, rng, bases);
      for (int q = 0; q < tile.pixels(); ++q) {
        if (tracer.survival(bases[size_t(q)], scratch) != settings.rr_min) continue;
        ++zero_bases;
        tracer.reuse().reuse(bases[size_t(q)], q, tile, fan, counters);
        bool light = false;
        for (int m = 0; m < tile.pixels(); ++m) light = light || (m != q && (fan.value[size_t(m)] > 0.0).any());
        zero_with_light += light;
      }
    }
    std::printf("gpr RR: %lld bases at q = q_min, %lld of them with shifted paths that carry light\n",
                (long long)zero_bases, (long long)zero_with_light);
    REQUIRE(zero_with_light > 50);
  }
  const Runs pt = pt_runs(*s, 2400);
  CHECK_FALSE(verdict("checker sphere, q_min 0.1", gpr_runs(*s, settings, 1400), pt).rejects());
  // q = min(1, lum / delta) without the floor: the zero-valued bases' fans are lost.
  GprSettings bad = settings;
  bad.faults.rr_without_floor = true;
  CHECK(verdict("checker sphere, fault: q without floor", gpr_runs(*s, bad, 1400), pt).rejects());
}

namespace {
struct FurnaceResult {
  int64_t pairs = 0, over = 0, exactly_zero = 0;
  double worst_ratio = 0;
};

// Every inner pair (i, j) of `tiles` tiles of the furnace: |gradient| against its
// round-off bound sum_k 2 eps(d_k) S_k / q_k. Each fan value is F_k->m = sum_p w_p v_p(m)
// with |v_p(m) - v_p(base)| <= eps v_p(base) (furnace_bound.h) and w_p <= 1, so
// |F_k->j - F_k->i| <= 2 eps S_k with S_k = sum_p v_p(base) (divided by the base's RR
// survival q_k); d_k is the shortest segment of walk k, its light samples and its reuse in
// i and j -- the reconnections x'_1 -> x_2 and x'_1 -> light, where x'_1 is the pixel's own
// primary hit (correlated primary rays).
FurnaceResult furnace(const GprSettings& settings, int tiles) {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, kRes);
  const GprTracer tracer(*s, settings, 10);
  std::vector<pathspace::Path> bases;
  gradients::PairTerms scratch;
  FurnaceResult out;
  auto dist = [](const Vec3& a, const Vec3& b) { return double((a - b).norm()); };
  for (int t = 0; t < tiles; ++t) {
    const ReuseTile inner{t % 3 * 5, t % 2 * 5, t % 3 * 5 + 6, t % 2 * 5 + 6};
    const ReuseTile ext = GprTracer::extended(inner, kRes, kRes);
    core::Rng rng(17, uint64_t(t));
    core::Rng replay = rng;
    tracer.reuse().build_bases(ext, replay, bases);
    const size_t n = bases.size();
    std::vector<double> own(n, std::numeric_limits<double>::infinity()), weight(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
      const pathspace::Path& x = bases[k];
      for (int v = 1; v < x.size(); ++v) {
        if (v + 1 < x.size() && x[v + 1].is_surface()) own[k] = std::min(own[k], dist(x[v].p(), x[v + 1].p()));
        if (x.nee[size_t(v)].valid) own[k] = std::min(own[k], dist(x[v].p(), x.nee[size_t(v)].p));
        weight[k] += double(pathspace::nee_estimate(x, v).maxCoeff());
        if (v >= 2) weight[k] += double(pathspace::emission_estimate(x, v).maxCoeff());
      }
      weight[k] /= tracer.survival(x, scratch);
    }
    // d_k of base k reused in pixel m (ext index).
    auto reuse_dist = [&](size_t k, int m) {
      const pathspace::Path &x = bases[k], &y = bases[size_t(m)];
      double d = own[k];
      if (x.size() > 2 && y.size() > 1) d = std::min(d, dist(y[1].p(), x[2].p()));
      if (x.size() > 1 && y.size() > 1 && x.nee[1].valid) d = std::min(d, dist(y[1].p(), x.nee[1].p));
      return d;
    };
    auto bound = [&](int i, int j) {
      double b = 0;
      for (size_t k = 0; k < n; ++k)
        b += 2.0 * test::furnace_roundoff_bound(std::min(reuse_dist(k, i), reuse_dist(k, j))) * weight[k];
      return b;
    };
    gradients::GradientBuffers buf(kRes, kRes);
    GprCounters counters;
    tracer.render_tile(inner, rng, buf, counters);
    REQUIRE(counters.reuse.shifts_full == counters.reuse.shifts);  // every reuse succeeds in the furnace
    const int tw = ext.width();
    auto check = [&](const Rgbd& g, double b) {
      const double a = g.abs().maxCoeff();
      ++out.pairs;
      out.exactly_zero += a == 0.0;
      out.over += a > b;
      out.worst_ratio = std::max(out.worst_ratio, a / b);
    };
    for (int y = inner.y0; y < inner.y1; ++y)
      for (int x = inner.x0; x < inner.x1; ++x) {
        const int m = (y - ext.y0) * tw + (x - ext.x0);
        if (x + 1 < ext.x1) check(buf.dx_sum(x, y), bound(m, m + 1));
        if (y + 1 < ext.y1) check(buf.dy_sum(x, y), bound(m, m + tw));
      }
  }
  return out;
}
}  // namespace

TEST_CASE("gpr furnace: every tile's gradients are zero within their round-off bound", "[unit]") {
  Settings s;
  const GprSettings settings = GprSettings::read(s);
  const FurnaceResult r = furnace(settings, 6);
  std::printf("gpr furnace: %lld inner pairs, %lld exactly 0, worst |grad| / bound %.2e, %lld over\n",
              (long long)r.pairs, (long long)r.exactly_zero, r.worst_ratio, (long long)r.over);
  CHECK(r.pairs > 6 * 60);
  CHECK(r.over == 0);
  // Reuse Jacobians forced to 1: the offsets' values are off by the reconnection factor.
  GprSettings bad = settings;
  bad.reuse.faults.jacobian = gradients::JacobianFault::unit;
  const FurnaceResult rb = furnace(bad, 6);
  std::printf("gpr furnace, fault: Jacobian = 1: worst |grad| / bound %.2e, %lld of %lld over\n", rb.worst_ratio,
              (long long)rb.over, (long long)rb.pairs);
  CHECK(rb.over > rb.pairs / 2);
}

