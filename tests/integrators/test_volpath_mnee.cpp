// volpath's manifold next-event estimation (integrators/volpath/volpath_mnee.h) on the
// caustic box filled with fog: the floor and the fog under the glass ball are lit only
// through the ball (L S+ D and L S+ M paths), plus the light reflected off it. MNEE with
// its MIS against BSDF/phase sampling must leave the image unchanged in expectation:
// volpath with MNEE (refraction and reflection chains) against volpath without it, per
// 8 x 8 block and the image mean, Welch's test over independent runs with a Sidak-corrected
// family level.
// Two real defects must be rejected by the same test: MNEE without MIS (the paths both
// strategies sample counted twice) and a planar D (1 / |y - s_m|^2 instead of the
// generalized geometry term d w_0 / dA(y)).
// Unit: MNEE's D = d w_0 / dA(y) against central differences of the chain traced in
// double from the anchor through the ball to the light's plane, for medium and floor
// anchors, refraction and reflection chains; the planar D is off.
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>
#include <cstdio>
#include <functional>
#include <string>

#include "integrators/volpath/volpath_integrator.h"
#include "integrators/volpath/volpath_tracer.h"
#include "manifold/local_geometry.h"
#include "manifold/walk.h"
#include "scene/loaders/loader.h"
#include "tests/support/block_stats.h"
#include "tests/support/quiet_options.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {

constexpr int kRes = 32, kBlock = 8, kRuns = 10, kSpp = 16, kDepth = 6;
// [0][run]: the image mean, [1 + b][run]: block b's mean (tests/support/block_stats.h).
test::BlockStats blocks(const scene::Scene& s, const integrators::VolpathSettings& vs, uint64_t seed0,
                        integrators::RenderResult* last = nullptr) {
  test::BlockStats out;
  for (int r = 0; r < kRuns; ++r) {
    integrators::VolpathIntegrator in(vs);
    integrators::RenderResult res = in.render(s, test::quiet_options(kSpp, seed0 + uint64_t(r), kDepth));
    test::add_block_run(out, res.layers[0].image, kBlock);
    if (last) *last = std::move(res);
  }
  return out;
}

// The end on the light's plane (y = 0.98) of the chain of `m` Dirac vertices (`mask` bit i:
// reflection) leaving o along d, traced in double; nullopt if it fails or, with `shape`
// >= 0, meets another shape.
std::optional<Vec3d> trace_to_light(const scene::Scene& s, Vec3d o, Vec3d d, Vec3d ng, int m, uint32_t mask,
                                    int shape = -1) {
  for (int i = 0; i < m; ++i) {
    const auto hit = manifold::trace(s, o, d, ng);
    if (!hit || (shape >= 0 && hit->shape != shape)) return std::nullopt;
    manifold::ChainVertex v;
    if (!manifold::local_frame(*s.shapes()[size_t(hit->shape)], hit->prim, hit->p, v.f)) return std::nullopt;
    const bool refl = ((mask >> i) & 1u) != 0;
    v.type = refl ? manifold::Interaction::reflection : manifold::Interaction::refraction;
    v.eta = refl ? 1.0 : 1.5;
    Vec3d w;
    if (manifold::scatter(v, -d, w) != manifold::WalkStatus::ok) return std::nullopt;
    o = v.p();
    d = w;
    ng = v.f.ng;
  }
  const double t = (0.98 - o.y()) / d.y();
  if (!(t > 0)) return std::nullopt;
  return o + t * d;
}

// D by central differences: w = normalize(w0 + a t1 + b t2) has solid angle da db at w0.
// A small step: near the ball's caustic the map bends fast (h = 1e-5 is off by 4 % there).
double fd_density(const scene::Scene& s, const Vec3d& o, const Vec3d& w0, const Vec3d& ng, int m, uint32_t mask,
                  double h = 1e-7) {
  const Frame f = Frame::from_normal(w0.cast<float>());
  const Vec3d t1 = (f.s.cast<double>() - w0 * w0.dot(f.s.cast<double>())).normalized(), t2 = w0.cross(t1);
  Vec2d col[2];
  for (int k = 0; k < 2; ++k) {
    const Vec3d t = k == 0 ? t1 : t2;
    const auto p = trace_to_light(s, o, (w0 + h * t).normalized(), ng, m, mask);
    const auto q = trace_to_light(s, o, (w0 - h * t).normalized(), ng, m, mask);
    if (!p || !q) return -1;
    col[k] = Vec2d(p->x() - q->x(), p->z() - q->z()) / (2 * h);
  }
  return 1.0 / std::abs(col[0].x() * col[1].y() - col[0].y() * col[1].x());
}

}  // namespace

TEST_CASE("volpath: MNEE's D = dw0/dA(y) agrees with finite differences", "[unit]") {
  const auto s = test::caustic_box(16, true);
  core::Rng rng(7);
  integrators::VolpathCounters c;
  integrators::VolpathSettings vs;
  vs.mnee_shapes = true;
  const integrators::VolpathTracer tracer(*s, vs, 16);
  integrators::VolpathSettings bad = vs;
  bad.fault = integrators::VolpathFault::mnee_planar_geometry;
  const integrators::VolpathTracer planar(*s, bad, 16);
  int checked[2] = {0, 0}, reflections = 0, planar_off = 0;
  double worst = 0;
  for (int i = 0; i < 400; ++i) {
    integrators::MneeAnchor a;
    a.medium = s->camera_medium();
    a.depth = 1;
    a.d_in = Vec3(0, -1, 0);
    // Medium anchors below the ball (refraction) and beside it above the shelf (reflection),
    // floor anchors below the ball.
    const bool floor = i % 3 == 1, upper = i % 3 == 2;
    const float side = rng.uniform() < 0.5f ? -1.0f : 1.0f;
    const Vec3 p = upper ? Vec3(side * (0.45f + 0.45f * rng.uniform()), 0.4f + 0.5f * rng.uniform(),
                                rng.uniform() * 1.6f - 0.8f)
                         : Vec3(rng.uniform() * 0.8f - 0.4f, floor ? 0.0f : -0.9f + 0.8f * rng.uniform(),
                                rng.uniform() * 0.8f - 0.4f);
    if (floor) {  // the floor point below p
      Ray r;
      r.o = p;
      r.d = Vec3(0, -1, 0);
      if (!s->intersect(r, a.hit) || a.hit.p.y() > -0.99f) continue;
      a.surface = true;
      a.wi_local = a.hit.shading.to_local(Vec3(0, 1, 0));
    } else {
      a.p = p;
    }
    const Vec3 y(rng.uniform() * 0.6f - 0.3f, 0.98f, rng.uniform() * 0.6f - 0.3f);
    const integrators::MneeSolutions S = tracer.mnee_connect(a, y, Vec3(0, -1, 0), 8, true, rng, c);
    const integrators::MneeSolutions P = planar.mnee_connect(a, y, Vec3(0, -1, 0), 8, true, rng, c);
    for (int k = 0; k < S.count; ++k) {
      const integrators::MneeConnection& X = S.x[size_t(k)];
      const Vec3d o = a.position().cast<double>();
      const Vec3d ng = a.surface ? Vec3d(a.hit.ng.cast<double>()) : Vec3d(Vec3d::Zero());
      const double D = fd_density(*s, o, (X.s1 - o).normalized(), ng, X.m, X.reflect_mask);
      if (!(D > 0)) continue;
      const double rel = std::abs(X.D / D - 1.0);
      worst = std::max(worst, rel);
      ++checked[floor ? 1 : 0];
      reflections += X.reflect_mask != 0;
      INFO("anchor " << o.transpose() << " y " << y.transpose() << " m " << X.m << " D " << X.D << " fd " << D);
      CHECK(rel < 1e-4);
      if (k < P.count && std::abs(P.x[size_t(k)].D / D - 1.0) > 0.1) ++planar_off;
    }
  }
  std::printf("[volpath MNEE D vs finite differences] %d medium and %d floor anchors' solutions (%d reflections), worst "
              "relative error %.2e; planar D off by > 10%% in %d\n",
              checked[0], checked[1], reflections, worst, planar_off);
  CHECK(checked[0] > 50);
  CHECK(checked[1] > 50);
  CHECK(reflections > 20);
  CHECK(planar_off > (checked[0] + checked[1]) * 9 / 10);
}

// A vertex above the light's plane sees only the back of the light (which faces down), but
// the light reflected off the ball below reaches it: NEE's light sample there must still be
// handed to MNEE, and MNEE's light density is the area density NEE sampled y with, not the
// straight line's solid-angle density (0 at the back). Both were missing: every reflection
// onto the ceiling of the volumetric-caustic scene was left to BSDF sampling (unbiased,
// MIS weight 1, but that 5 x 4 mm light is practically never hit).
TEST_CASE("volpath: MNEE reaches the light from behind its plane", "[unit]") {
  const auto s = test::caustic_box(16, true);
  integrators::VolpathSettings vs;
  vs.mnee_shapes = true;
  const integrators::VolpathTracer tracer(*s, vs, 16);
  core::Rng rng(11);
  integrators::VolpathCounters c;
  const Vec3 x(0.6f, 0.99f, 0.05f);  // in the fog between the light (y 0.98) and the ceiling
  const int medium = s->camera_medium();
  int probed = 0, solved = 0, found = 0;
  double worst = 0;
  for (int i = 0; i < 200; ++i) {
    integrators::NeeProbe probe;
    tracer.next_event_medium(x, Vec3(0, 1, 0), medium, rng, c, &probe);
    probed += probe.area_light;
    if (!probe.area_light) continue;
    integrators::MneeAnchor a;
    a.p = x;
    a.medium = medium;
    a.depth = 1;
    a.d_in = Vec3(0, 1, 0);
    const integrators::MneeSolutions S = tracer.mnee_connect(a, probe.y, probe.n, 8, probe.try_chain, rng, c);
    found += S.count > 0;
    for (int k = 0; k < S.count; ++k) {
      const integrators::MneeConnection& X = S.x[size_t(k)];
      if (X.reflect_mask != 1u || !(X.value.maxCoeff() > 0.0f)) continue;
      ++solved;
      // NEE samples the 0.6 x 0.6 light uniformly by area; the box has one light.
      worst = std::max(worst, std::abs(X.p_light * 0.36 - 1.0));
    }
  }
  std::printf("[volpath MNEE behind the light] %d of 200 NEE samples handed to MNEE, %d with solutions, %d reflections; "
              "light density worst relative error %.1e\n",
              probed, found, solved, worst);
  CHECK(probed == 200);
  CHECK(solved > 100);
  CHECK(worst < 1e-5);
}

TEST_CASE("volpath: MNEE with MIS leaves the fogged caustic box unchanged; two MNEE defects are rejected", "[stat]") {
  const auto s = test::caustic_box(kRes, true);
  REQUIRE(s->caps().has_media);
  integrators::VolpathSettings off;
  off.mnee = false;
  integrators::VolpathSettings on;
  on.mnee = true;
  on.mnee_shapes = true;
  on.light_tracing = true;
  integrators::RenderResult last;
  const test::BlockStats plain = blocks(*s, off, 100);
  const test::BlockStats mnee = blocks(*s, on, 200, &last);
  // It did what the scene asks for: chains solved on the NEE side, and BSDF/phase paths
  // through the ball that MNEE also returns (so both MIS weights were exercised).
  CHECK(last.stats.get("volpath.mnee.chains") > 0);
  CHECK(last.stats.get("volpath.mnee.connections") > 0);
  CHECK(last.stats.get("volpath.mnee.shape_attempts") > 0);
  CHECK(last.stats.get("volpath.mnee.bsdf_matched") > 0);
  // Light tracing (volpath_light.cpp) joined light paths through
  // the ball to the camera and to camera-path vertices, and MNEE returned their chains.
  CHECK(last.stats.get("volpath.light.chains") > 0);
  CHECK(last.stats.get("volpath.light.added") > 0);
  CHECK(last.info["light_paths"].number() > 0.0);
  CHECK(last.stats.get("volpath.nan_dropped") == 0);
  const double worst = test::sidak_welch(mnee, plain, 0.01);

  // The defects on the straight family only (the caustic; cheaper than the shape families).
  integrators::VolpathSettings no_mis = on;
  no_mis.mnee_shapes = false;
  no_mis.fault = integrators::VolpathFault::mnee_without_mis;
  const double worst_no_mis = test::sidak_welch(blocks(*s, no_mis, 300), plain, 0.01);
  integrators::VolpathSettings planar = no_mis;
  planar.fault = integrators::VolpathFault::mnee_planar_geometry;
  const double worst_planar = test::sidak_welch(blocks(*s, planar, 400), plain, 0.01);
  integrators::VolpathSettings lt_no_mis = on;  // light tracing's paths counted a second time
  lt_no_mis.mnee_shapes = false;
  lt_no_mis.fault = integrators::VolpathFault::light_tracing_without_mis;
  const double worst_lt = test::sidak_welch(blocks(*s, lt_no_mis, 500), plain, 0.01);
  std::printf("[volpath MNEE vs none, fogged caustic box] worst |t|/crit %.2f; without MIS %.2f; planar D %.2f; "
              "light tracing without MIS %.2f; chains %lld, connections %lld, light paths joined %lld, BSDF paths "
              "matched %lld of %lld\n",
              worst, worst_no_mis, worst_planar, worst_lt, (long long)last.stats.get("volpath.mnee.chains"),
              (long long)last.stats.get("volpath.mnee.connections"), (long long)last.stats.get("volpath.light.added"),
              (long long)last.stats.get("volpath.mnee.bsdf_matched"),
              (long long)last.stats.get("volpath.mnee.bsdf_hits"));
  CHECK(worst < 1.0);
  CHECK(worst_no_mis > 1.0);
  CHECK(worst_planar > 1.0);
  CHECK(worst_lt > 1.0);
}

// MNEE's scanned seeds (mnee_scan; integrators/volpath/volpath_mnee_scan.cpp) against every
// solution of the ball lens of the caustic box: for fog anchors below the ball (inside and
// around its caustic, where up to three chains through the ball reach one light point)
// and inside it (one refraction out), a dense reference scan in double of 20000 directions
// in the plane of the anchor, the centre and y (every solution of a ball lies in it),
// across the ball's silhouette (or the whole circle from inside), with each sign change of
// the miss refined by bisection. A root is "isolated" when its neighbours are at least two
// steps of the default scan away (in the scan's own parameter), and from outside the
// silhouette one: the scan must bracket each such root and its walk must reach it. Over
// all roots (fold pairs included), the share of sum D (the light the solutions carry) the
// scan returns must not be below the fixed seeds' (mnee_scan = 0, the earlier default).
// Below the ball, with the fixed seeds in the scan's place two isolated roots are missed
// (sum D share 0.992); an 8-direction scan returns 0.935, the scan without its run-end
// seeds 0.958. Inside, the fixed seeds return 0.987, a scan over half the circle 104 of
// the 300 solutions.
namespace {

struct ScanRecall {
  int anchors = 0, roots = 0, isolated = 0, isolated_found = 0, three = 0, n_scan = 0, n_fixed = 0;
  double d_all = 0, d_scan = 0, d_fixed = 0;
};

ScanRecall scan_recall(bool inside, uint64_t seed) {
  const auto s = test::caustic_box(16, true);
  const Vec3d centre(0.0, 0.3, 0.0);
  const double radius = 0.4;
  const int ball = int(s->shapes().size()) - 1;  // caustic_box adds it last
  const int m = inside ? 1 : 2;
  const integrators::VolpathSettings scan;  // the default scan
  REQUIRE(scan.mnee_scan > 0);
  integrators::VolpathSettings fixed;
  fixed.mnee_scan = 0;
  const integrators::VolpathTracer scanned(*s, scan, 16), seeded(*s, fixed, 16);
  core::Rng rng(seed);
  integrators::VolpathCounters c;
  ScanRecall out;
  for (int i = 0; i < 300; ++i) {
    // Inside: above the shelf's plane (y 0.3), which cuts the ball outside |x|, |z| < 0.25.
    const Vec3 p = inside ? Vec3(rng.uniform() * 0.24f - 0.12f, 0.35f + 0.27f * rng.uniform(), rng.uniform() * 0.24f - 0.12f)
                          : Vec3(rng.uniform() * 0.5f - 0.25f, -0.95f + 0.75f * rng.uniform(), rng.uniform() * 0.5f - 0.25f);
    const Vec3 y(rng.uniform() * 0.6f - 0.3f, 0.98f, rng.uniform() * 0.6f - 0.3f);
    Ray straight;
    straight.o = p;
    straight.d = (y - p).normalized();
    scene::SurfaceHit h;
    if (!s->intersect(straight, h) || h.shape != ball) continue;  // the ball blocks x -> y
    ++out.anchors;
    // The reference: e(theta) = (landing - y) . a, theta from the direction to the centre.
    const Vec3d o = p.cast<double>(), yd = y.cast<double>();
    const Vec3d to_c = centre - o;
    const double dc = to_c.norm(), theta_max = inside ? kPiD : std::asin(radius / dc);
    const Vec3d normal = to_c.cross(yd - o).normalized(), cdir = to_c / dc, u = normal.cross(cdir).normalized();
    const Vec3d a = Vec3d(0, -1, 0).cross(normal).normalized();
    auto dir = [&](double t) { return Vec3d(std::cos(t) * cdir + std::sin(t) * u); };
    auto miss = [&](double t) -> std::optional<double> {
      const auto end = trace_to_light(*s, o, dir(t), Vec3d::Zero(), m, 0u, ball);
      if (!end) return std::nullopt;
      return (*end - yd).dot(a);
    };
    constexpr int kDense = 20000;
    std::vector<double> roots;
    std::optional<double> prev = miss(-theta_max);
    double t_prev = -theta_max;
    for (int j = 1; j <= kDense; ++j) {
      const double t = -theta_max + 2.0 * theta_max * double(j) / kDense;
      const std::optional<double> e = miss(t);
      if (prev && e && (*prev <= 0) != (*e <= 0)) {
        double lo = t_prev, hi = t, e_lo = *prev;
        for (int b = 0; b < 60; ++b) {
          const double mid = 0.5 * (lo + hi);
          const auto em = miss(mid);
          if (!em) break;
          if ((*em <= 0) == (e_lo <= 0)) lo = mid, e_lo = *em;
          else hi = mid;
        }
        roots.push_back(0.5 * (lo + hi));
      }
      prev = e;
      t_prev = t;
    }
    const integrators::MneeAnchor x = integrators::MneeAnchor::in_medium(p, Vec3(0, -1, 0), s->camera_medium(), 1);
    const integrators::MneeSolutions S = scanned.mnee_connect(x, y, Vec3(0, -1, 0), 8, true, rng, c);
    const integrators::MneeSolutions F = seeded.mnee_connect(x, y, Vec3(0, -1, 0), 8, true, rng, c);
    auto has = [&](const integrators::MneeSolutions& set, const Vec3d& s1) {
      for (int k = 0; k < set.count; ++k)
        if (set.x[size_t(k)].m == m && (set.x[size_t(k)].s1 - s1).norm() < 1e-4) return true;
      return false;
    };
    // The scan's parameter (volpath_mnee_scan.cpp): sin theta = (R / d_c) sin t from
    // outside, theta = 2 t from inside; pi / K per step.
    auto param = [&](double th) {
      return inside ? 0.5 * th : std::asin(std::clamp(std::sin(th) * dc / radius, -1.0, 1.0));
    };
    const double step = kPiD / scan.mnee_scan;
    out.three += roots.size() == 3;
    for (size_t r = 0; r < roots.size(); ++r) {
      const auto hit = manifold::trace(*s, o, dir(roots[r]), Vec3d::Zero());
      REQUIRE(hit);
      const double D = fd_density(*s, o, dir(roots[r]), Vec3d::Zero(), m, 0u);
      ++out.roots;
      const bool in_scan = has(S, hit->p), in_fixed = has(F, hit->p);
      out.n_scan += in_scan;
      out.n_fixed += in_fixed;
      if (D > 0) {
        out.d_all += D;
        out.d_scan += in_scan ? D : 0.0;
        out.d_fixed += in_fixed ? D : 0.0;
      }
      // Half the distance to the neighbouring roots (around the circle from inside); from
      // outside the distance to the silhouette (the scan's outermost samples lie half a
      // step inside it).
      const double t_r = param(roots[r]);
      const double wrap = inside ? kPiD : 0.0;
      const double lo = r > 0 ? 0.5 * (t_r - param(roots[r - 1]))
                              : inside ? 0.5 * (t_r - param(roots.back()) + wrap) : t_r + 0.5 * kPiD;
      const double hi = r + 1 < roots.size() ? 0.5 * (param(roots[r + 1]) - t_r)
                                             : inside ? 0.5 * (param(roots.front()) + wrap - t_r) : 0.5 * kPiD - t_r;
      if (roots.size() > 1 || !inside)
        if (std::min(lo, hi) < step) continue;
      ++out.isolated;
      out.isolated_found += in_scan;
      INFO("anchor " << o.transpose() << " y " << yd.transpose() << " root " << roots[r] << " of " << roots.size()
                     << ", theta_max " << theta_max);
      CHECK(in_scan);
    }
  }
  std::printf("[volpath MNEE scan vs a dense reference, anchors %s the ball] %d anchors (%d with three solutions), "
              "%d solutions (%d isolated, %d of them found); returned: scan %d (share of sum D %.4f), fixed seeds %d "
              "(%.4f)\n",
              inside ? "inside" : "below", out.anchors, out.three, out.roots, out.isolated, out.isolated_found,
              out.n_scan, out.d_scan / out.d_all, out.n_fixed, out.d_fixed / out.d_all);
  std::printf("  scan: %lld brackets, %lld folds, %lld run ends, %lld fallbacks\n", (long long)c.mnee_scan_brackets,
              (long long)c.mnee_scan_folds, (long long)c.mnee_scan_edges, (long long)c.mnee_scan_fallbacks);
  CHECK(out.anchors > 100);
  CHECK(out.isolated > out.roots / 2);
  CHECK(out.d_scan >= out.d_fixed);
  return out;
}

}  // namespace

TEST_CASE("volpath: MNEE's scanned seeds reach every isolated solution of a ball lens", "[unit]") {
  SECTION("anchors below the ball, two refractions") {
    const ScanRecall r = scan_recall(false, 5);
    CHECK(r.three > 10);  // anchors inside the caustic (three solutions)
  }
  SECTION("anchors inside the ball, one refraction") { scan_recall(true, 6); }
}

// A glass slab made of six quads (as Mitsuba `rectangle`s make one): the first refracting
// shape the straight segment meets is flat, its bounds have no thickness. The scan must
// still span the face's width: every anchor below the slab with a solution for the fixed
// seeds has one for the scan, found by the scan's own brackets rather than by its
// fallback walk from the straight line. (Scanning across the bounds' smallest extent,
// zero here, collapsed every scan direction onto one: no bracket, and before the
// fallback no solution at all.)
TEST_CASE("volpath: MNEE's scan reaches the light through a slab of flat faces", "[unit]") {
  std::string yaml = R"(version: 1
camera: {type: perspective, position: [0, 0.5, -3], look_at: [0, 0.5, 0], up: [0, 1, 0], fov: 40, resolution: [8, 8]}
materials:
  white: {type: diffuse, albedo: [0.7, 0.7, 0.7]}
  glass: {type: dielectric, ior: 1.5, ext_ior: 1.0}
media:
  fog: {type: homogeneous, sigma_a: [0.01, 0.01, 0.01], sigma_s: [0.1, 0.1, 0.1], phase: {type: isotropic}}
medium: fog
shapes:
  - {type: quad, material: white, vertices: [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]}
  - {type: quad, emission: [10, 10, 10], vertices: [[-0.2, 2, -0.2], [0.2, 2, -0.2], [0.2, 2, 0.2], [-0.2, 2, 0.2]]}
)";
  // The slab x, z in [-0.6, 0.6], y in [1.0, 1.1], outward normals.
  const float a = 0.6f, y0 = 1.0f, y1 = 1.1f;
  auto face = [&](std::initializer_list<Vec3> v) {
    yaml += "  - {type: quad, material: glass, vertices: [";
    for (const Vec3& p : v) yaml += "[" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + "], ";
    yaml.resize(yaml.size() - 2);
    yaml += "]}\n";
  };
  face({{-a, y1, -a}, {-a, y1, a}, {a, y1, a}, {a, y1, -a}});
  face({{-a, y0, -a}, {a, y0, -a}, {a, y0, a}, {-a, y0, a}});
  face({{-a, y0, -a}, {-a, y1, -a}, {a, y1, -a}, {a, y0, -a}});
  face({{-a, y0, a}, {a, y0, a}, {a, y1, a}, {-a, y1, a}});
  face({{-a, y0, -a}, {-a, y0, a}, {-a, y1, a}, {-a, y1, -a}});
  face({{a, y0, -a}, {a, y1, -a}, {a, y1, a}, {a, y0, a}});
  const auto s = scene::load_scene_yaml_string(yaml, "slab.yaml");
  const integrators::VolpathSettings scan;
  integrators::VolpathSettings fixed;
  fixed.mnee_scan = 0;
  const integrators::VolpathTracer scanned(*s, scan, 16), seeded(*s, fixed, 16);
  core::Rng rng(9);
  integrators::VolpathCounters c;
  int with_fixed = 0, with_scan = 0, missed = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 p(rng.uniform() - 0.5f, 0.1f + 0.8f * rng.uniform(), rng.uniform() - 0.5f);
    const Vec3 y(0.4f * rng.uniform() - 0.2f, 2.0f, 0.4f * rng.uniform() - 0.2f);
    const integrators::MneeAnchor x = integrators::MneeAnchor::in_medium(p, Vec3(0, -1, 0), s->camera_medium(), 1);
    const int n_scan = scanned.mnee_connect(x, y, Vec3(0, -1, 0), 8, true, rng, c).count;
    const int n_fixed = seeded.mnee_connect(x, y, Vec3(0, -1, 0), 8, true, rng, c).count;
    with_fixed += n_fixed > 0;
    with_scan += n_scan > 0;
    missed += n_fixed > 0 && n_scan == 0;
  }
  std::printf("[volpath MNEE scan through a slab of quads] 200 anchors: solutions for %d with the fixed seeds, %d with "
              "the scan, %d missed by the scan; scans %lld bracketed, %lld fell back to the straight line\n",
              with_fixed, with_scan, missed, (long long)c.mnee_scan_brackets, (long long)c.mnee_scan_fallbacks);
  CHECK(with_fixed > 150);
  CHECK(missed == 0);
  CHECK(c.mnee_scan_brackets > 4 * c.mnee_scan_fallbacks);  // the scan itself, not its fallback, found them
}
