// NaN injection: one sphere of lit_box gets a test-only BSDF (tests/support/nan_bsdf.h)
// that returns NaN at a fraction p of its vertices (decided by a hash of wi, so the
// renders are reproducible and thread-count independent). Every registered integrator
// must drop those samples (counted in its "*.nan_dropped" counters) and keep every
// pixel of every output layer finite.
//
// Bounds on the drop counters, derived, not tuned:
//  * drops > 0: with p = 0.02 and thousands of sphere vertices, zero injections is
//    impossible (the test also requires injected() > 0 first).
//  * Each drop is one estimate (a PT camera path, a G-PT pixel pair, an MCMC proposal or
//    bootstrap sample, a GD-MLT direct-pass path) that made its own BSDF calls, at least
//    one of which returned NaN (the BSDF is the only NaN source in this scene). One
//    NaN-returning call is part of exactly one estimate, except in G-PT where the base
//    path's calls are shared by the 4 neighbour pairs of its sample (gpt_tracer.cpp: one
//    drop per pair; the direct term base[1].emission involves no BSDF call). Hence
//      drops <= injected          (pt, mlt, gdmlt + gdmlt.direct)
//      drops <= 4 * injected      (gpt).
//  * PT at max_depth 2 (camera -> surface -> light): the sphere can only be the first
//    vertex, so a camera path is one Bernoulli trial. A render at p = 1 with the same
//    seed gives D1 = the number of camera paths whose value depends on the sphere's BSDF
//    (the measured fraction D1 / paths is the fraction of paths that hit the sphere and
//    see the light by NEE or BSDF sampling). At p the number of dropped paths is then
//    Binomial(D1, p): the trial is "the hash of this path's wi is below p 2^64". The
//    test requires drops inside the central interval of that binomial at a two-sided
//    false-alarm level of 1e-6 (it fails if an integrator drops finite paths too, or
//    lets NaN paths into the image: the finiteness check catches those).
//    Why the two renders trace the same paths: at max_depth 2 no path's use of the
//    tile's random stream depends on a NaN (next_event() draws its 3 numbers before any
//    early return, sample() its 3 unconditionally, Russian roulette starts at depth
//    rr_depth = 5 and the depth-2 vertex ends the walk before any draw), so the set of
//    D1 "NaN-reachable" paths is the same at p and at 1; what is left random is the hash
//    of each path's wi, treated as an independent uniform 64-bit value (splitmix64 of
//    distinct float bits). Beyond depth 2 this breaks (a NaN throughput changes the RR
//    draws and the number of bounces), which is why the binomial case is depth 2 only.
//    (Cross-check over seeds 1..10 at 32x32, 64 spp: mean drops 407 vs. p D1 = 401, sd
//    of that mean 6; at p = 0.5 4013 vs 4010. Seed 7: D1 8040, drops 438, interval
//    [309, 501].)
//    Power: D1 ~ 8000, so the interval is p D1 +- ~5 sd = 400 +- ~100: counting each
//    drop twice, or dropping every sphere path, fails.
//  * Watched failing: a local copy of path_integrator.cpp that counted non-finite paths
//    but splatted them (linked over the library's object, not committed) gave 16
//    non-finite pixels in the first test and 169 / 147 in the binomial one; a local copy
//    of gpt_tracer.cpp without the `continue` after its finiteness check (counted but
//    splatted) gave 420 non-finite pixels over G-PT's layers.
//  * Not covered: a partial under-count in G-PT or the MCMC integrators (e.g. mlt
//    forgetting the bootstrap's invalid samples) stays within 0 < drops <= injected;
//    only PT has an exact lower bound (the binomial case).
#include <catch2/catch.hpp>

#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <memory>

#include "integrators/integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/nan_bsdf.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
std::shared_ptr<test::NanBsdf> nan_sphere(double p) {
  return std::make_shared<test::NanBsdf>(scene::make_diffuse(scene::constant_texture(Rgb(0.6f, 0.5f, 0.4f))), p);
}

integrators::RenderResult render(const scene::Scene& s, const std::string& name, int spp, int max_depth) {
  integrators::Settings settings;
  if (name == "mlt" || name == "gdmlt" || name == "memlt") settings.set("bootstrap", "5000");
  auto in = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = 7;
  opt.threads = 2;
  opt.max_depth = max_depth;
  opt.quiet = true;
  return in->render(s, opt);
}

int64_t nonfinite_pixels(const integrators::RenderResult& r) {
  int64_t n = 0;
  for (const auto& layer : r.layers)
    for (const Rgb& c : layer.image.pixels()) n += c.isFinite().all() ? 0 : 1;
  return n;
}

int64_t nan_dropped(const integrators::RenderResult& r, const std::string& name) {
  if (name == "path") return r.stats.get("pt.nan_dropped");
  if (name == "gdmlt") return r.stats.get("gdmlt.nan_dropped") + r.stats.get("gdmlt.direct.nan_dropped");
  return r.stats.get(name + ".nan_dropped");
}
}  // namespace

TEST_CASE("nan injection: every integrator drops NaN samples and keeps every layer finite", "[render]") {
  const std::vector<std::string> names = integrators::integrator_names();
  REQUIRE(names.size() >= 4);
  for (const std::string& name : names) {
    INFO("integrator " << name);
    auto bsdf = nan_sphere(0.02);
    const auto s = test::lit_box(bsdf, nullptr, 32);
    const auto r = render(*s, name, 8, 6);
    const int64_t injected = bsdf->injected();
    const int64_t drops = nan_dropped(r, name);
    INFO("injected " << injected << ", dropped " << drops);
    REQUIRE(!r.layers.empty());
    CHECK(nonfinite_pixels(r) == 0);
    REQUIRE(injected > 0);
    CHECK(drops > 0);
    const int64_t per_call = name == "gpt" ? 4 : 1;  // see the header comment
    CHECK(drops <= per_call * injected);
  }
}

TEST_CASE("nan injection: PT drops a binomial number of direct-lighting paths", "[render][stat]") {
  constexpr int kRes = 32, kSpp = 64, kDepth = 2;
  constexpr double kP = 0.05, kAlpha = 1e-6;
  const int64_t paths = int64_t(kRes) * kRes * kSpp;

  auto all = nan_sphere(1.0);
  const auto r1 = render(*test::lit_box(all, nullptr, kRes), "path", kSpp, kDepth);
  REQUIRE(r1.stats.get("pt.paths") == paths);
  const int64_t d1 = r1.stats.get("pt.nan_dropped");
  CHECK(nonfinite_pixels(r1) == 0);
  // The sphere (radius 0.4, 1.6 from the camera) covers a few percent of the view.
  REQUIRE(d1 > paths / 50);
  REQUIRE(d1 < paths / 2);

  auto some = nan_sphere(kP);
  const auto rp = render(*test::lit_box(some, nullptr, kRes), "path", kSpp, kDepth);
  const int64_t drops = rp.stats.get("pt.nan_dropped");
  CHECK(nonfinite_pixels(rp) == 0);

  const boost::math::binomial_distribution<double> b(double(d1), kP);
  const double lo = boost::math::quantile(b, kAlpha / 2), hi = boost::math::quantile(boost::math::complement(b, kAlpha / 2));
  INFO("paths " << paths << ", hit fraction " << double(d1) / double(paths) << ", D1 " << d1 << ", drops " << drops
                << ", binomial interval [" << lo << ", " << hi << "], injected " << some->injected());
  CHECK(double(drops) >= std::floor(lo));
  CHECK(double(drops) <= std::ceil(hi));
  // Each dropped path made at least one NaN-returning call.
  CHECK(drops <= some->injected());
}
