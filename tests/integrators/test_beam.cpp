// The primal photon beams `beam` (issue 15; integrators/beam/): its BVH, its two
// estimators on a field with a known answer, the volumetric furnace and volpath.
//  * BVH: the beam query returns exactly the brute-force set (every beam whose segment is
//    within r of the camera segment, the exact segment distance checked against a dense
//    grid), unsplit and with beams split into pieces; rejects BeamFault::bvh_unpadded
//    (node boxes not grown by r: beams missed);
//  * a synthetic isotropic beam field of known line density: both kernels recover
//    lambda sigma_s / (4 pi) int_0^l Tr_c (t-test over independent fields); rejects the
//    dropped chord pdf (3D), the dropped camera transmittance (both) and the dropped
//    1 / sin(theta) (1D);
//  * the light pass: beams do not change the photons (bit-identical), and every photon
//    ends a beam of its depth and medium (the depth convention);
//  * furnace (media_furnace_support.h): the image mean within the kernel's derived bias
//    bound, per kernel; rejects the defects above and short beams weighted as long ones;
//  * the media box: the image mean agrees with volpath's (Welch over runs), both kernels,
//    and a defect of each kernel is rejected;
//  * without media no beam is traced and no medium code runs; with media the image
//    depends on the seed only and parts add up.
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "integrators/beam/beam_bvh.h"
#include "integrators/beam/beam_gather.h"
#include "integrators/beam/beam_integrator.h"
#include "integrators/integrator.h"
#include "integrators/media_photons/photon_tracer.h"
#include "tests/integrators/media_furnace_support.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;
using integrators::BeamFault;
using integrators::BeamKernel;
using integrators::MediumBeam;

namespace {

struct BeamConfig {
  BeamKernel kernel = BeamKernel::k3d;
  BeamFault fault = BeamFault::none;
  int photons = 20000;
  double radius_scale = 0.01, alpha = 0.7;
};

const char* kernel_label(BeamKernel k) { return k == BeamKernel::k3d ? "3d" : "1d"; }

integrators::RenderResult render_beam(const scene::Scene& s, const BeamConfig& c, int iterations, uint64_t seed,
                                      int max_depth) {
  integrators::BeamSettings b;
  b.photons = c.photons;
  b.radius_scale = c.radius_scale;
  b.radius_alpha = c.alpha;
  b.kernel = c.kernel;
  b.fault = c.fault;
  return integrators::BeamIntegrator(b).render(s, test::quiet_options(iterations, seed, max_depth));
}

double beam_image_mean(const core::Image& img) {
  double s = 0;
  for (const auto& p : img.pixels()) s += double(p.sum());
  return s / double(img.size());
}

Vec3 random_direction(core::Rng& rng) { return core::warp::square_to_uniform_sphere(rng.uniform2()); }

std::vector<MediumBeam> random_beams(int n, core::Rng& rng) {
  std::vector<MediumBeam> out(static_cast<size_t>(n));
  for (size_t i = 0; i < out.size(); ++i) {
    MediumBeam& b = out[i];
    b.a = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f;
    b.w = i % 7 == 0 ? Vec3(Vec3::Unit(int(i / 7 % 3))) : random_direction(rng);  // some axis-aligned
    b.length = 0.5f * rng.uniform();
    b.beta = Rgb::Ones();
    b.depth = 1;
    b.medium = 0;
    b.index = uint32_t(i);
  }
  return out;
}

}  // namespace

TEST_CASE("beam: the segment distance and the BVH beam query equal brute force", "[unit]") {
  core::Rng rng(11, 0);
  // The exact segment distance against a dense grid over (s, t): the grid minimum is never
  // below the exact one, and at most (h_s + h_t) / 2 above it (the distance is 1-Lipschitz
  // in s and in t; the optimum is within half a cell of a node).
  double worst_gap = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 p0 = Vec3(rng.uniform(), rng.uniform(), rng.uniform()), q0 = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    Vec3 u = random_direction(rng), v = random_direction(rng);
    if (k % 10 == 0) v = u;  // parallel
    if (k % 10 == 1) v = -u;
    const double S = 1.5 * double(rng.uniform()), T = 1.5 * double(rng.uniform());
    const double exact = std::sqrt(integrators::beam_segment_distance2(p0, u, S, q0, v, T));
    constexpr int kGrid = 301;
    double grid = 1e30;
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const double s = S * i / (kGrid - 1), t = T * j / (kGrid - 1);
        grid = std::min(grid, (p0.cast<double>() + s * u.cast<double>() - q0.cast<double>() - t * v.cast<double>()).norm());
      }
    CHECK(exact <= grid + 1e-6);
    CHECK(grid <= exact + 0.5 * (S + T) / (kGrid - 1) + 1e-6);
    worst_gap = std::max(worst_gap, grid - exact);
  }
  std::printf("[beam distance] worst grid - exact %.2e\n", worst_gap);

  // Beams of length up to 0.5, unsplit and split into pieces of at most 0.1: the query
  // reports pieces; the set of beams they belong to must be the brute-force set.
  const auto beams = random_beams(4000, rng);
  integrators::BeamBvh bvh, split;
  bvh.build(beams);
  split.build(beams, 0.1f);
  REQUIRE(bvh.size() == beams.size());
  REQUIRE(bvh.pieces() == beams.size());
  REQUIRE(split.pieces() > 2 * beams.size());
  int64_t found = 0, mismatched_queries = 0, unpadded_mismatches = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 o = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.4f - Vec3::Constant(0.2f);
    Vec3 d = random_direction(rng);
    if (q % 3 == 0) d = Vec3::Unit(q % 9 / 3);  // the slab test's 0 * inf case
    const float tmax = q % 5 == 0 ? kInfinity : 2.0f * rng.uniform();
    const float r = 0.01f + 0.1f * rng.uniform();
    // Brute force over every beam; an unbounded segment is cut at 100 (every beam lies
    // within 3 of every origin, so nothing beyond can be within r).
    const double t_brute = std::isfinite(tmax) ? double(tmax) : 100.0;
    std::vector<uint32_t> brute, got, pieces, unpadded;
    for (const auto& b : beams)
      if (integrators::beam_segment_distance2(o, d, t_brute, b.a, b.w, double(b.length)) <= double(r) * double(r))
        brute.push_back(b.index);
    auto unique_sorted = [](std::vector<uint32_t>& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    bool whole = true;  // the unsplit BVH reports each beam once, as its whole range
    bvh.query_segment(o, d, tmax, r, [&](const MediumBeam& b, float v0, float v1) {
      got.push_back(b.index);
      whole = whole && v0 == 0.0f && v1 == b.length;
    });
    split.query_segment(o, d, tmax, r, [&](const MediumBeam& b, float, float) { pieces.push_back(b.index); });
    split.query_segment(o, d, tmax, r, [&](const MediumBeam& b, float, float) { unpadded.push_back(b.index); }, false);
    CHECK(whole);
    std::sort(got.begin(), got.end());
    unique_sorted(pieces);
    unique_sorted(unpadded);
    mismatched_queries += got == brute && pieces == brute ? 0 : 1;
    unpadded_mismatches += unpadded == brute ? 0 : 1;
    found += int64_t(got.size());
  }
  std::printf("[beam bvh] %lld beams found over 300 queries; mismatches %lld, with the planted unpadded boxes %lld\n",
              (long long)found, (long long)mismatched_queries, (long long)unpadded_mismatches);
  CHECK(mismatched_queries == 0);
  CHECK(found > 1000);  // the queries were not empty
  // The planted defect (BeamFault::bvh_unpadded) misses beams in many queries.
  CHECK(unpadded_mismatches > 10);
}

namespace {

// A synthetic isotropic beam field (the uniform photon field of test_media_kernels for
// beams): n beams of length l_b whose midpoints are uniform in [0, 4]^3 and directions
// uniform on the sphere. At any point deeper than l_b / 2 inside the cube the expected
// beam length per unit volume is lambda = n l_b / 64, uniform over directions. With
// beta = 1 in a grey medium (sigma_a = 0, sigma_s = sigma_t = sigma: Tr_b(v) / P(v) = 1)
// and an isotropic phase function, both estimators' expectation along a camera segment of
// length l is (beam_gather.h)
//   E = lambda sigma_s / (4 pi) int_0^l exp(-sigma t) dt      (3D: the kernel integrates
// to 1 where the field is uniform; 1D: the Jacobian sin(theta) of the closest-point
// parameters cancels the 1 / sin(theta)).
struct FieldResult {
  std::vector<double> field_means;  // per field: the mean over its queries
};

FieldResult field_estimates(BeamKernel kernel, BeamFault fault, int fields, int n) {
  scene::HomogeneousMedium med;
  med.sigma_a = Rgb::Zero();
  med.sigma_s = Rgb::Constant(0.5f);
  med.phase.type = scene::PhaseFunctionDesc::Type::hg;
  med.phase.g = 0.0f;
  const float r = 0.1f, len = 2.0f;
  FieldResult out;
  for (int f = 0; f < fields; ++f) {
    core::Rng rng(900 + uint64_t(f), 3);
    std::vector<MediumBeam> beams(static_cast<size_t>(n));
    for (size_t i = 0; i < beams.size(); ++i) {
      MediumBeam& b = beams[i];
      const Vec3 mid = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f;
      b.w = random_direction(rng);
      b.length = 1.0f;
      b.a = mid - 0.5f * b.w;
      b.beta = Rgb::Ones();
      b.depth = 1;
      b.medium = 0;
      b.index = uint32_t(i);
    }
    integrators::BeamBvh bvh;
    bvh.build(std::move(beams), 0.3f);  // pieces of 0.3: the partition of each beam is exercised
    double sum = 0;
    int queries = 0;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        // Segments along x from x = 1 to 3: every point within r of them is >= 0.6 deep.
        const Vec3 c(1.0f, 1.0f + 0.5f * float(i), 1.0f + 0.5f * float(j)), w(1, 0, 0);
        integrators::GatherCounters counters;
        Rgbd est = Rgbd::Zero();
        bvh.query_segment(c, w, len, r, [&](const MediumBeam& b, float v0, float v1) {
          const Rgb v = kernel == BeamKernel::k3d
                            ? integrators::beam_beam_3d(med, b, v0, v1, c, w, len, r, rng.uniform(), fault)
                            : integrators::beam_beam_1d(med, b, v0, v1, c, w, len, r, counters, fault);
          est += v.cast<double>();
        });
        sum += est[0];
        ++queries;
      }
    out.field_means.push_back(sum / queries);
  }
  return out;
}

}  // namespace

TEST_CASE("beam: both estimators recover a synthetic beam field's known answer", "[unit]") {
  constexpr int kFields = 8, kBeams = 40000;
  const double lambda = kBeams * 1.0 / 64.0, sigma = 0.5, len = 2.0;
  const double expected = lambda * sigma / (4.0 * double(kPi)) * -std::expm1(-sigma * len) / sigma;
  // Two-sided t at 1e-3 over the fields (independent: their spread is the estimator's se).
  const double t_crit =
      boost::math::quantile(boost::math::complement(boost::math::students_t(double(kFields - 1)), 0.5e-3));
  struct Case {
    BeamKernel kernel;
    BeamFault fault;
  };
  for (const Case c : {Case{BeamKernel::k3d, BeamFault::none}, Case{BeamKernel::k1d, BeamFault::none},
                       Case{BeamKernel::k3d, BeamFault::no_chord_pdf},
                       Case{BeamKernel::k3d, BeamFault::no_camera_transmittance},
                       Case{BeamKernel::k1d, BeamFault::no_camera_transmittance},
                       Case{BeamKernel::k1d, BeamFault::no_sin_theta}}) {
    const FieldResult r = field_estimates(c.kernel, c.fault, kFields, kBeams);
    const test::Moments m = test::moments(r.field_means);
    const double t = (m.mean - expected) / std::sqrt(m.var / double(m.n));
    std::printf("[beam field %s fault %d] mean %.3f (expected %.3f, se %.3f): |t|/crit %.2f\n", kernel_label(c.kernel),
                int(c.fault), m.mean, expected, std::sqrt(m.var / double(m.n)), std::abs(t) / t_crit);
    if (c.fault == BeamFault::none) CHECK(std::abs(t) < t_crit);
    else CHECK(std::abs(t) > t_crit);
  }
}

TEST_CASE("beam: recording beams leaves the photons unchanged; photons end beams of their depth", "[unit]") {
  const auto s = test::media_box(true, 16);
  integrators::PhotonTraceParams tp;
  tp.paths = 5000;  // two chunks
  tp.max_depth = 8;
  tp.seed = 5;
  tp.threads = 2;
  std::vector<integrators::MediumPhoton> plain, recorded;
  std::vector<MediumBeam> beams;
  integrators::PhotonTraceCounters c1, c2;
  integrators::BeamTraceCounters bc;
  REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, plain, c1));
  REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, recorded, c2, nullptr, &beams, &bc));
  REQUIRE(plain.size() == recorded.size());
  REQUIRE(!plain.empty());
  bool same = true;
  for (size_t i = 0; i < plain.size(); ++i)
    same = same && plain[i].p == recorded[i].p && (plain[i].beta == recorded[i].beta).all() &&
           plain[i].depth == recorded[i].depth;
  CHECK(same);
  CHECK(c1.stored == c2.stored);
  CHECK(c1.surface_events == c2.surface_events);
  CHECK(bc.stored == int64_t(beams.size()));
  CHECK(beams.size() > plain.size());  // every photon ends a beam; passes make more
  CHECK(bc.dropped == 0);
  CHECK(bc.clipped == 0);  // a closed box: no beam reaches the grown bounds
  // Every photon is the end of a beam of its depth and medium, with the photon's
  // throughput = the beam's times the scatter's weight (so >= 0 where the beam's is).
  int64_t matched = 0;
  size_t next = 0;  // beams and photons are both in traced order: search forward
  for (const auto& ph : recorded) {
    bool found = false;
    for (size_t k = next; k < beams.size() && !found; ++k) {
      const MediumBeam& b = beams[k];
      const Vec3 end = b.a + b.length * b.w;
      if ((end - ph.p).norm() <= 1e-4f * (1.0f + ph.p.norm()) && b.depth == ph.depth && b.medium == ph.medium &&
          (b.w - ph.w).norm() < 1e-6f) {
        found = true;
        next = k + 1;
      }
    }
    matched += found ? 1 : 0;
  }
  std::printf("[beam light pass] %zu photons, %zu beams, %lld photons matched to a beam end\n", recorded.size(),
              beams.size(), (long long)matched);
  CHECK(matched == int64_t(recorded.size()));
  bool depths = true;
  for (const auto& b : beams) depths = depths && b.depth >= 1 && b.depth <= tp.max_depth - 1 && b.length > 0.0f;
  CHECK(depths);
  // Photons off: the same beams.
  tp.store_photons = false;
  std::vector<integrators::MediumPhoton> none;
  std::vector<MediumBeam> beams2;
  integrators::BeamTraceCounters bc2;
  REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, none, c2, nullptr, &beams2, &bc2));
  CHECK(none.empty());
  REQUIRE(beams2.size() == beams.size());
  bool same_beams = true;
  for (size_t i = 0; i < beams.size(); ++i)
    same_beams = same_beams && beams[i].a == beams2[i].a && beams[i].length == beams2[i].length &&
                 (beams[i].beta == beams2[i].beta).all();
  CHECK(same_beams);
}

TEST_CASE("beam: the volumetric furnace renders the environment within the kernel's bias bound", "[stat]") {
  constexpr int kRes = 24, kIter = 4, kRuns = 6, kDepth = 1000;
  const Rgb env = test::kFurnaceEnv;
  const auto s = test::medium_furnace(test::furnace_medium(), env, false, kRes);
  const double diag = double(s->bounds().diagonal());
  // 2 kernels x 3 channels at 1% family-wise (Sidak), two-sided, on the runs' means.
  const double z = boost::math::quantile(boost::math::normal(), 1.0 - (1.0 - std::pow(0.99, 1.0 / 6.0)) / 2.0);
  // Bias bound (beam_gather.h): the pixel's expectation differs from env only through the
  // kernel mass lost outside the ball for camera points within r of its surface (the
  // radiance field inside is env in every direction), at most 1/2 of a 3D kernel (convex
  // medium) and all of a 1D one (both halves of a chord-like line can leave the ball):
  // |mean - env| <= f sigma_s env x (mean ray length in the shell), f = 1/2 (3D), 1 (1D).
  auto check = [&](const BeamConfig& c, bool expect_pass) {
    const double r1 = c.radius_scale * diag;  // the largest radius (alpha < 1 shrinks it)
    const double shell = test::shell_length(*s, r1);
    const double f = c.kernel == BeamKernel::k3d ? 0.5 : 1.0;
    double worst = 0;
    int64_t stored = 0, candidates = 0;
    test::Runs runs;
    for (int k = 0; k < kRuns; ++k) {
      const auto r = render_beam(*s, c, kIter, 100 + uint64_t(k), kDepth);
      stored += r.stats.get("beam.beams_stored");
      candidates += r.stats.get("beam.beam_candidates");
      CHECK(r.stats.get("beam.nan_dropped") == 0);
      CHECK(r.stats.get("beam.beam_nan_dropped") == 0);
      const core::Image& img = r.layers[0].image;
      test::add_run(runs, {test::channel_mean(img, 0), test::channel_mean(img, 1), test::channel_mean(img, 2)});
    }
    for (int ch = 0; ch < 3; ++ch) {
      const test::Moments m = test::moments(runs[size_t(ch)]);
      const double se = std::sqrt(m.var / double(m.n));
      const double bound = f * double(test::furnace_medium().sigma_s[ch]) * double(env[ch]) * shell;
      const double excess = (std::abs(m.mean - double(env[ch])) - bound) / se;
      std::printf("[beam furnace %s] fault %d ch %d: mean %.4f (env %.2f, bias bound %.4f, se %.4f) excess/se %.2f\n",
                  kernel_label(c.kernel), int(c.fault), ch, m.mean, double(env[ch]), bound, se, excess);
      worst = std::max(worst, excess);
    }
    CHECK(stored > 0);
    CHECK(candidates > 0);
    if (expect_pass) CHECK(worst < z);
    else CHECK(worst > z);
  };
  for (BeamKernel k : {BeamKernel::k3d, BeamKernel::k1d}) {
    BeamConfig c;
    c.kernel = k;
    check(c, true);
  }
  // The defects (each rejected): 3D without the chord pdf, short beams weighted as long
  // ones (chromatic sigma_t: Tr_c / P differs from 1 per channel), no camera transmittance;
  // 1D without 1 / sin(theta) and without the pass probability.
  struct Case {
    BeamKernel kernel;
    BeamFault fault;
  };
  for (const Case d : {Case{BeamKernel::k3d, BeamFault::no_chord_pdf}, Case{BeamKernel::k3d, BeamFault::no_pass_probability},
                       Case{BeamKernel::k3d, BeamFault::no_camera_transmittance},
                       Case{BeamKernel::k1d, BeamFault::no_sin_theta}, Case{BeamKernel::k1d, BeamFault::no_pass_probability}}) {
    BeamConfig c;
    c.kernel = d.kernel;
    c.fault = d.fault;
    check(c, false);
  }
}

namespace {

constexpr int kBeamBoxRes = 32, kBeamBoxDepth = 8, kBeamBoxRuns = 8;

const test::Runs& beam_volpath_reference(const scene::Scene& s) {
  static test::Runs ref;
  if (!ref.empty()) return ref;
  for (int k = 0; k < kBeamBoxRuns; ++k) {
    integrators::Settings settings;
    auto in = integrators::make_integrator("volpath", settings);
    test::add_run(ref, {beam_image_mean(in->render(s, test::quiet_options(32, 500 + uint64_t(k), kBeamBoxDepth)).layers[0].image)});
  }
  return ref;
}

}  // namespace

TEST_CASE("beam: converges to volpath's image mean on a box with media, both kernels", "[stat]") {
  const auto s = test::media_box(true, kBeamBoxRes);
  const test::Runs& ref = beam_volpath_reference(*s);
  struct Case {
    BeamKernel kernel;
    BeamFault fault;
  };
  // The defects: short beams weighted as long ones (3D; the box's media are chromatic),
  // the 1D kernel without 1 / sin(theta).
  for (const Case d : {Case{BeamKernel::k3d, BeamFault::none}, Case{BeamKernel::k1d, BeamFault::none},
                       Case{BeamKernel::k3d, BeamFault::no_pass_probability},
                       Case{BeamKernel::k1d, BeamFault::no_sin_theta}}) {
    BeamConfig c;
    c.kernel = d.kernel;
    c.fault = d.fault;
    c.photons = 5000;
    test::Runs runs;
    for (int k = 0; k < kBeamBoxRuns; ++k)
      test::add_run(runs, {beam_image_mean(render_beam(*s, c, 4, 700 + uint64_t(k), kBeamBoxDepth).layers[0].image)});
    const double ratio = test::welch_ratio(test::moments(runs[0]), test::moments(ref[0]), 0.01);
    std::printf("[beam %s fault %d vs volpath, media box] image mean %.4f (se %.4f) vs %.4f (se %.4f): |t|/crit %.2f\n",
                kernel_label(c.kernel), int(c.fault), test::moments(runs[0]).mean,
                std::sqrt(test::moments(runs[0]).var / kBeamBoxRuns), test::moments(ref[0]).mean,
                std::sqrt(test::moments(ref[0]).var / kBeamBoxRuns), ratio);
    if (d.fault == BeamFault::none) CHECK(ratio < 1.0);
    else CHECK(ratio > 1.0);
  }
}

TEST_CASE("beam: without media no beam is traced and no medium code runs", "[unit]") {
  const auto s = test::lit_box(nullptr, nullptr, 16);
  REQUIRE_FALSE(s->caps().has_media);
  for (BeamKernel k : {BeamKernel::k3d, BeamKernel::k1d}) {
    BeamConfig c;
    c.kernel = k;
    auto r = render_beam(*s, c, 3, 4, kBeamBoxDepth);
    CHECK(r.stats.get("beam.iterations") == 3);
    CHECK(r.stats.get("beam.photon_passes_skipped") == 3);
    CHECK(r.stats.get("beam.photon_paths") == 0);
    CHECK(r.stats.counters().count("beam.beams_stored") == 1);
    CHECK(r.stats.get("beam.beams_stored") == 0);
    CHECK(r.stats.get("beam.camera_paths") == 3 * 16 * 16);
    CHECK(r.stats.get("beam.media_skipped") == 3 * 16 * 16);
    CHECK(r.stats.get("beam.medium_segments") + r.stats.get("beam.queries") + r.stats.get("beam.beam_candidates") == 0);
    CHECK(r.info["media"].dump().find("false") != std::string::npos);
    CHECK(r.min_spp == 3);
    // With media the same counters show the beam work (planted: a scene with media fails
    // every zero check above).
    const auto m = render_beam(*test::media_box(false, 16), c, 1, 4, kBeamBoxDepth);
    CHECK(m.stats.get("beam.beams_stored") > 0);
    CHECK(m.stats.get("beam.photons_stored") == 0);
    CHECK(m.stats.get("beam.queries") > 0);
    CHECK(m.stats.get("beam.beam_candidates") > 0);
    CHECK(m.stats.get("beam.contributions") > 0);
    CHECK(m.stats.get("beam.contributions") <= m.stats.get("beam.beam_candidates"));
    CHECK(m.stats.get("beam.media_skipped") == 0);
  }
}

TEST_CASE("beam: with media the image depends on the seed only, and parts add up", "[unit]") {
  const auto s = test::media_box(true, 16);
  for (BeamKernel k : {BeamKernel::k3d, BeamKernel::k1d}) {
    integrators::BeamSettings b;
    b.kernel = k;
    b.photons = 5000;  // two light-path chunks
    b.radius_scale = 0.02;
    integrators::BeamIntegrator in(b);
    auto opt = test::quiet_options(3, 21, kBeamBoxDepth);
    opt.threads = 1;
    const auto one = in.render(*s, opt);
    opt.threads = 2;
    const auto two = in.render(*s, opt);
    opt.seed = 22;
    const auto other = in.render(*s, opt);
    REQUIRE(one.stats.get("beam.beams_stored") > 0);
    bool same = true, differs = false;
    for (size_t i = 0; i < one.layers[0].image.size(); ++i) {
      same = same && (one.layers[0].image[i] == two.layers[0].image[i]).all();
      differs = differs || !(one.layers[0].image[i] == other.layers[0].image[i]).all();
    }
    CHECK(same);
    CHECK(differs);
    auto popt = test::quiet_options(4, 21, kBeamBoxDepth);
    popt.raw = true;
    const auto whole = in.render(*s, popt);
    core::RawImage sum;
    for (int part = 0; part < 3; ++part) {
      popt.part = part;
      popt.parts = 3;
      const auto pr = in.render(*s, popt);
      if (part == 0) sum = pr.raw;
      else sum.add(pr.raw);
    }
    CHECK(sum.counts.at("spp") == whole.raw.counts.at("spp"));
    double worst = 0;
    const auto& a = sum.sums.at("radiance");
    const auto& w = whole.raw.sums.at("radiance");
    for (size_t i = 0; i < w.size(); ++i) worst = std::max(worst, ((a[i] - w[i]).abs() / (w[i].abs() + 1e-300)).maxCoeff());
    CHECK(worst < 1e-12);
  }
}
