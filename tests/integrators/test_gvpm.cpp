// Gradient-domain volumetric photon mapping `gvpm` (issue 15; docs/gvpm_plan.md, Sec. 4),
// against the volumetric furnace, vpm and volpath:
//  * furnace (test_vpm_bre's: an index-matched albedo-1 ball under a uniform environment;
//    10 runs x 16 iterations, 24x24): the L2 reconstruction's image mean lies within vpm's
//    kernel-bias bound (1/2 sigma_s env x the camera ray's length within r of the sphere)
//    plus the runs' z margin; the image means of dx and dy are 0 within z (the ball does
//    not reach the image border, so the forward differences telescope to 0); the primal's
//    mean agrees with vpm's at the same settings (Welch, Sidak over the channels: gvpm's
//    primal estimates the same kernel-biased expectation). Per-sample gradients are not 0
//    here: a reconnected photon's weight changes with t^2/t'^2 and Tr, only the null shift
//    would leave base and offset equal, and at these radii the kernels do not overlap.
//    Measured: worst excess/(z se) 0.63, primal vs vpm |t|/crit 0.56; with kernels 4x as
//    wide (r > the gather points' offset: 0.92M null and 0.76M reflected mixed shifts
//    over the runs) 0.63 and 0.13.
//    Planted defects, rejected: the offset's gather density without Eq. 14's truncation
//    (MIS weights no longer sum to 1): primal vs vpm |t|/crit 1.43; MIS weight 1 on both
//    sides of a pair (Eq. 19 left out): 8.49 (recon_l2 excess/(z se) 7.70);
//  * media box with fog (test_vpm_bre's, 32x32, fixed radius 1% of the diagonal, 8 runs x
//    16 iterations vs volpath 8 runs x 128 spp): the L2 reconstruction's image mean agrees
//    with volpath's (Welch), and the 4x4-block means of dx / dy (plus the pixel
//    differences of the unshifted `direct` layer) agree with volpath's pixel differences
//    over the same pixels (Welch per block, Sidak over the 128 blocks, family-wise 1%).
//    Measured: mean |t|/crit 0.30, blocks worst 0.50. Planted defects, rejected: MIS
//    weight 1 (mean 9.31), untruncated offset density (mean 5.14), the reconnection
//    without the volume measure's 1/t^2 (ReconnectFault::no_volume_factor; blocks 1.80);
//  * without media: no photon traced, every sample's light in `direct`, gradients 0
//    (counters); with media the image depends on the seed only (1 vs 2 threads) and 3
//    parts' raw buffers add up to the whole render's; the photon tracer's photons are
//    bit-identical with and without parent records (vpm/bre do not record them), and the
//    media box has light, surface, medium and specular parents.
// `gbre` and `gbeam` (G-BRE, G-Beam) run the same furnace and media box (primal against
// `bre --set kernel=3d` / `beam`); each also rejects its own density defect
// (GvpmFault::chord_as_diameter, GvpmFault::beam_chord_ignored). gbeam runs a tenth of the
// light paths (its terms per query are ~10x gbre's at equal paths).
// `gplane` (G-Plane) runs the furnace at a tenth of the light paths against `plane`
// (primal |t|/crit 0.27, worst excess/(z se) 0.97) and the media box at 16x16 (L2 mean
// 0.22, blocks 0.34), rejecting MIS weight 1 (furnace 8.87, box mean 1.44); its Jacobian
// defect (Eq. 18's printed t-factors) is rejected by test_volume_plane_shift and by the
// hidden [.] media box case at 32x32 (blocks 1.63), not at the budgets CI runs.
#include <boost/math/distributions/normal.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/rng.h"
#include "integrators/beam/beam_integrator.h"
#include "integrators/bre/bre_integrator.h"
#include "integrators/gvpm/gvpm_integrator.h"
#include "integrators/integrator.h"
#include "integrators/media_photons/photon_tracer.h"
#include "integrators/plane/plane_integrator.h"
#include "integrators/vpm/vpm_integrator.h"
#include "tests/integrators/media_furnace_support.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;
using integrators::GvpmFault;

namespace {

struct Config {
  GvpmFault fault = GvpmFault::none;
  gradients::ReconnectFault reconnect_fault = gradients::ReconnectFault::none;
  int photons = 20000;
  double radius_scale = 0.01, radius_alpha = 0.7;
  int distance_samples = 4;
  integrators::GvpmGather gather = integrators::GvpmGather::points;  // gvpm | gbre | gbeam
  std::string prefix() const {
    integrators::GvpmSettings g;
    g.gather = gather;
    return g.name();
  }
};

integrators::RenderResult render(const scene::Scene& s, const Config& c, int iterations, uint64_t seed, int max_depth) {
  integrators::GvpmSettings g;
  g.photons = c.photons;
  g.radius_scale = c.radius_scale;
  g.radius_alpha = c.radius_alpha;
  g.distance_samples = c.distance_samples;
  g.fault = c.fault;
  g.reconnect_fault = c.reconnect_fault;
  g.gather = c.gather;
  return integrators::GvpmIntegrator(g).render(s, test::quiet_options(iterations, seed, max_depth));
}

const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  FAIL("no layer " << name);
  return r.layers[0].image;
}

using test::add_run;
using test::furnace_medium;
using test::Runs;
using test::shell_length;
const Rgb kEnv = test::kFurnaceEnv;

}  // namespace

namespace {

// The planted defect of each gather mode's own density (besides MIS weight 1).
GvpmFault density_fault(integrators::GvpmGather gather) {
  if (gather == integrators::GvpmGather::beam) return GvpmFault::chord_as_diameter;
  if (gather == integrators::GvpmGather::beams) return GvpmFault::beam_chord_ignored;
  if (gather == integrators::GvpmGather::planes) return GvpmFault::plane_eq18_jacobian;
  return GvpmFault::untruncated_offset_pdf;
}

// gbeam and gplane run a tenth of the light paths (each gives several beams or planes,
// each meeting many queries: ~10x gbre's terms per query at equal paths).
bool few_paths(integrators::GvpmGather gather) {
  return gather == integrators::GvpmGather::beams || gather == integrators::GvpmGather::planes;
}

void furnace_test(integrators::GvpmGather gather) {
  const bool beam = gather == integrators::GvpmGather::beam, beams = gather == integrators::GvpmGather::beams;
  const bool planes = gather == integrators::GvpmGather::planes;
  constexpr int kRes = 24, kIter = 16, kRuns = 10, kDepth = 1000;
  const auto s = test::medium_furnace(furnace_medium(), kEnv, false, kRes);
  const double diag = double(s->bounds().diagonal());
  // 9 statistics (recon_l2, dx, dy x 3 channels) at 1% family-wise (Sidak), two-sided.
  const double z = boost::math::quantile(boost::math::normal(), 1.0 - (1.0 - std::pow(0.99, 1.0 / 9.0)) / 2.0);
  // vpm (gbre: bre with kernel=3d) at the same settings: the primal estimates the same
  // (kernel-biased) expectation.
  auto vpm_runs = [&](double radius_scale, int photons) {
    Runs runs;
    for (int k = 0; k < kRuns; ++k) {
      integrators::VpmSettings v;
      integrators::BreSettings b;
      integrators::BeamSettings bm;
      integrators::PlaneSettings pl;
      v.photons = b.photons = bm.photons = pl.photons = photons;
      v.radius_scale = b.radius_scale = bm.radius_scale = pl.radius_scale = radius_scale;
      v.radius_alpha = b.radius_alpha = bm.radius_alpha = pl.radius_alpha = Config{}.radius_alpha;
      v.distance_samples = Config{}.distance_samples;
      b.kernel_dim = 3;
      const auto opt = test::quiet_options(kIter, 300 + uint64_t(k), kDepth);
      const auto r = planes ? integrators::PlaneIntegrator(pl).render(*s, opt)
                     : beams  ? integrators::BeamIntegrator(bm).render(*s, opt)
                     : beam ? integrators::BreIntegrator(b).render(*s, opt)
                            : integrators::VpmIntegrator(v).render(*s, opt);
      add_run(runs, {test::channel_mean(r.layers[0].image, 0), test::channel_mean(r.layers[0].image, 1),
                     test::channel_mean(r.layers[0].image, 2)});
    }
    return runs;
  };
  const int photons = few_paths(gather) ? Config{}.photons / 10 : Config{}.photons;
  const Runs vpm_default = vpm_runs(Config{}.radius_scale, photons);
  auto check = [&](Config c, bool expect_pass) {
    c.gather = gather;
    if (few_paths(gather)) c.photons /= 10;
    const std::string p = c.prefix();
    const double shell = shell_length(*s, c.radius_scale * diag);
    Runs runs, primal;
    int64_t shifted = 0, reconnections = 0, nulls = 0, reflected = 0;
    for (int k = 0; k < kRuns; ++k) {
      const auto r = render(*s, c, kIter, 100 + uint64_t(k), kDepth);
      CHECK(r.stats.get(p + ".nan_dropped") == 0);
      shifted += r.stats.get(p + ".pairs.shifted");
      reconnections += r.stats.get(p + (planes ? ".shift.plane_rotations" : ".shift.reconnections"));
      nulls += r.stats.get(p + ".shift.null");
      reflected += r.stats.get(p + ".shift.reflected");
      std::vector<double> v;
      for (const char* name : {"recon_l2", "dx", "dy"})
        for (int ch = 0; ch < 3; ++ch) v.push_back(test::channel_mean(layer(r, name), ch));
      add_run(runs, v);
      const core::Image& pr = layer(r, "primal");
      add_run(primal, {test::channel_mean(pr, 0), test::channel_mean(pr, 1), test::channel_mean(pr, 2)});
    }
    double worst = 0;  // in units of the critical value
    for (size_t i = 0; i < runs.size(); ++i) {
      const int ch = int(i % 3);
      const bool gradient = i >= 3;
      const test::Moments m = test::moments(runs[i]);
      const double se = std::sqrt(m.var / double(m.n));
      const double expect = gradient ? 0.0 : double(kEnv[ch]);
      const double bound = gradient ? 0.0 : 0.5 * double(furnace_medium().sigma_s[ch]) * double(kEnv[ch]) * shell;
      const double excess = (std::abs(m.mean - expect) - bound) / se;
      worst = std::max(worst, excess / z);
      std::printf("[%s furnace] fault %d %s ch %d: mean %.5f (expect %.2f, bias bound %.4f, se %.5f) excess/se %.2f\n",
                  p.c_str(), int(c.fault), i < 3 ? "recon_l2" : i < 6 ? "dx" : "dy", ch, m.mean, expect, bound, se, excess);
    }
    const double vs_vpm =
        test::sidak_welch(primal, c.radius_scale == Config{}.radius_scale ? vpm_default : vpm_runs(c.radius_scale, c.photons), 0.01);
    std::printf("[%s furnace] fault %d: primal vs %s worst |t|/crit %.2f; pairs shifted %lld, reconnections %lld, null "
                "shifts %lld, reflected %lld; worst excess/(se z) %.2f (z %.2f)\n",
                p.c_str(), int(c.fault), planes ? "plane" : beams ? "beam" : beam ? "bre 3d" : "vpm", vs_vpm, (long long)shifted, (long long)reconnections, (long long)nulls,
                (long long)reflected, worst, z);
    worst = std::max(worst, vs_vpm);
    CHECK(shifted > 0);
    CHECK(reconnections > 0);
    if (c.radius_scale > Config{}.radius_scale) CHECK((nulls > 0 && reflected > 0));
    if (expect_pass) CHECK(worst < 1.0);
    else CHECK(worst > 1.0);
  };
  check(Config{}, true);
  if (!planes) {  // Kernels wider than a pixel's offset: null and reflected (mixed) shifts occur.
    Config wide;
    wide.radius_scale = 0.04;
    wide.photons = 5000;  // 16x the photons per query of the default config at a quarter of the paths
    check(wide, true);
  }
  // gplane: Eq. 18's Jacobian changes each pair by ~1% here (neighbouring rays, t' ~ t):
  // not rejected at this budget (measured 0.77); the unit test rejects it
  // (test_volume_plane_shift.cpp), and the media box at 32x32 ([.] case below).
  std::vector<GvpmFault> faults = {GvpmFault::mis_weight_one};
  if (!planes) faults.push_back(density_fault(gather));
  for (auto f : faults) {
    Config c;
    c.fault = f;
    check(c, false);
  }
}

}  // namespace

TEST_CASE("gvpm: the volumetric furnace: reconstruction within vpm's bias bound, gradients summing to 0", "[stat]") {
  furnace_test(integrators::GvpmGather::points);
}

TEST_CASE("gbeam: the volumetric furnace: reconstruction within beam's bias bound, gradients summing to 0", "[stat]") {
  furnace_test(integrators::GvpmGather::beams);
}

TEST_CASE("gplane: the volumetric furnace: reconstruction within the beam part's bias bound, gradients summing to 0",
          "[stat]") {
  furnace_test(integrators::GvpmGather::planes);
}

TEST_CASE("gbre: the volumetric furnace: reconstruction within bre 3d's bias bound, gradients summing to 0", "[stat]") {
  furnace_test(integrators::GvpmGather::beam);
}

namespace {

constexpr int kBoxRes = 32, kBoxBlock = 4, kBoxDepth = 8, kBoxRuns = 8, kBoxIterations = 16;

// One reference per resolution (the scenes differ only in it).
const Runs& volpath_reference(const scene::Scene& s) {
  static std::map<int, Runs> refs;
  Runs& ref = refs[s.camera().width()];
  if (!ref.empty()) return ref;
  for (int k = 0; k < kBoxRuns; ++k) {
    integrators::Settings settings;
    auto in = integrators::make_integrator("volpath", settings);
    const auto r = in->render(s, test::quiet_options(kBoxIterations * 8, 500 + uint64_t(k), kBoxDepth));
    add_run(ref, test::gradient_blocks(r.layers[0].image, nullptr, nullptr, nullptr, kBoxBlock));
  }
  return ref;
}

// The planted defects: `defects` (default: MIS weight 1, the mode's density defect and,
// for modes that reconnect, the reconnection without 1/t^2).
enum class Defects { all, mis_only, density_only };

void media_box_test(integrators::GvpmGather gather, int res = kBoxRes, Defects defects = Defects::all) {
  const auto s = test::media_box(true, res);
  const Runs& ref = volpath_reference(*s);
  auto runs_of = [&](const Config& c) {
    Runs runs;
    int64_t shifted = 0, fallback = 0;
    for (int k = 0; k < kBoxRuns; ++k) {
      const auto r = render(*s, c, kBoxIterations, 700 + uint64_t(k), kBoxDepth);
      shifted += r.stats.get(c.prefix() + ".pairs.shifted");
      fallback += r.stats.get(c.prefix() + ".pairs.fallback");
      std::vector<double> v =
          test::gradient_blocks(layer(r, "recon_l2"), &layer(r, "dx"), &layer(r, "dy"), &layer(r, "direct"), kBoxBlock);
      add_run(runs, v);
    }
    std::printf("[%s media box] fault %d: pairs shifted %lld, fallback %lld\n", c.prefix().c_str(), int(c.fault),
                (long long)shifted, (long long)fallback);
    return runs;
  };
  Config c;
  c.photons = few_paths(gather) ? 1000 : 5000;  // see few_paths
  c.radius_scale = 0.01;
  c.radius_alpha = 1.0;
  c.gather = gather;
  const Runs runs = runs_of(c);
  const double mean_ratio = test::welch_ratio(test::moments(runs[0]), test::moments(ref[0]), 0.01);
  const Runs blocks(runs.begin() + 1, runs.end()), ref_blocks(ref.begin() + 1, ref.end());
  const double block_ratio = test::sidak_welch(blocks, ref_blocks, 0.01);
  std::printf("[%s vs volpath, media box] L2 image mean %.4f vs %.4f: |t|/crit %.2f; dx/dy blocks worst |t|/crit %.2f\n",
              c.prefix().c_str(), test::moments(runs[0]).mean, test::moments(ref[0]).mean, mean_ratio, block_ratio);
  CHECK(mean_ratio < 1.0);
  CHECK(block_ratio < 1.0);
  // Planted defects, each rejected by the image mean or the blocks.
  // gbeam: the reconnection (shared with gvpm and gbre, which reject its defect 2) is
  // not re-tested: at gbeam's photon count its block statistic is not powerful enough.
  // gplane: no reconnection to test.
  const bool reconnects = gather != integrators::GvpmGather::beams && gather != integrators::GvpmGather::planes;
  for (int d = 0; d < (reconnects ? 3 : 2); ++d) {
    if ((defects == Defects::mis_only && d != 0) || (defects == Defects::density_only && d != 1)) continue;
    Config bad = c;
    if (d == 0) bad.fault = GvpmFault::mis_weight_one;
    if (d == 1) bad.fault = density_fault(c.gather);
    if (d == 2) bad.reconnect_fault = gradients::ReconnectFault::no_volume_factor;
    const Runs bad_runs = runs_of(bad);
    const Runs bad_blocks(bad_runs.begin() + 1, bad_runs.end());
    const double bad_mean = test::welch_ratio(test::moments(bad_runs[0]), test::moments(ref[0]), 0.01);
    const double bad_ratio = test::sidak_welch(bad_blocks, ref_blocks, 0.01);
    std::printf("[%s vs volpath, media box] defect %d: L2 mean |t|/crit %.2f, dx/dy blocks worst |t|/crit %.2f\n",
                c.prefix().c_str(), d, bad_mean, bad_ratio);
    CHECK(std::max(bad_mean, bad_ratio) > 1.0);
  }
}

}  // namespace

// gbeam's box plants MIS weight 1 only: its density defect (the beam photon not divided by
// 1/|chord_b|) is rejected by the furnace above at |t|/crit ~68 (box: ~75), and the box's
// third run set cost ~25 s of CI (session 18).
TEST_CASE("gbeam: L2 reconstruction and dx/dy blocks agree with volpath on a box with media", "[stat]") {
  media_box_test(integrators::GvpmGather::beams, kBoxRes, Defects::mis_only);
}

// gplane at 16x16 (a quarter of the 32x32 cost: each plane meets ~700 primary segments at
// 1000 paths) with MIS weight 1 as its planted defect. Eq. 18's Jacobian is rejected at
// 32x32 by the hidden case below (run it by its tag: build/test_gvpm "[gplane_eq18]"; not
// [stat], which would select it in CI; 6.5 min; measured: correct mean 0.35 / blocks 0.71,
// Eq. 18 blocks 1.63, MIS weight 1 mean 5.48); at 16x16 it measured 1.00, no power.
TEST_CASE("gplane: L2 reconstruction and dx/dy blocks agree with volpath on a box with media", "[stat]") {
  media_box_test(integrators::GvpmGather::planes, 16, Defects::mis_only);
}

TEST_CASE("gplane: the media box at 32x32 rejects Eq. 18's printed Jacobian", "[.][gplane_eq18]") {
  media_box_test(integrators::GvpmGather::planes, kBoxRes, Defects::density_only);
}

TEST_CASE("gvpm: L2 reconstruction and dx/dy blocks agree with volpath on a box with media", "[stat]") {
  media_box_test(integrators::GvpmGather::points);
}

TEST_CASE("gbre: L2 reconstruction and dx/dy blocks agree with volpath on a box with media", "[stat]") {
  media_box_test(integrators::GvpmGather::beam);
}

TEST_CASE("gvpm: without media no photon is traced; with media seed-only determinism and parts add up", "[unit]") {
  {
    const auto s = test::lit_box(nullptr, nullptr, 16);
    REQUIRE_FALSE(s->caps().has_media);
    const auto r = render(*s, Config{}, 3, 4, kBoxDepth);
    CHECK(r.stats.get("gvpm.iterations") == 3);
    CHECK(r.stats.get("gvpm.photon_passes_skipped") == 3);
    CHECK(r.stats.get("gvpm.photon_paths") == 0);
    CHECK(r.stats.get("gvpm.samples") == 3 * 16 * 16);
    CHECK(r.stats.get("gvpm.media_skipped") == 3 * 16 * 16);
    CHECK(r.stats.get("gvpm.primary_segments") + r.stats.get("gvpm.shift.attempted") == 0);
    double g = 0;
    for (const char* name : {"dx", "dy"})
      for (const auto& p : layer(r, name).pixels()) g += double(p.abs().sum());
    CHECK(g == 0.0);
    CHECK(r.min_spp == 3);
  }
  const auto s = test::media_box(true, 16);
  {  // parent records do not change the photons (planted defect: the record drawn from the
     // path's own stream instead of a copy: the photon count differs, REQUIRE fails)
    integrators::PhotonTraceParams tp;
    tp.paths = 9000;
    tp.max_depth = kBoxDepth;
    tp.seed = 5;
    tp.threads = 2;
    std::vector<integrators::MediumPhoton> plain, recorded;
    std::vector<gradients::PhotonParent> parents;
    integrators::PhotonTraceCounters c1, c2;
    REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, plain, c1));
    REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, recorded, c2, &parents));
    REQUIRE(plain.size() == recorded.size());
    REQUIRE(parents.size() == recorded.size());
    bool same = !plain.empty();
    int64_t kinds[gradients::kParentKindCount] = {};
    for (size_t i = 0; i < plain.size(); ++i) {
      same = same && plain[i].p == recorded[i].p && (plain[i].beta == recorded[i].beta).all() &&
             recorded[i].index == uint32_t(i);
      ++kinds[int(parents[i].kind)];
    }
    CHECK(same);
    // The box has all kinds of parents but the infinite light: area light, walls, the
    // glass ball (specular), the smoke and the fog.
    CHECK(kinds[int(gradients::ParentKind::light)] > 0);
    CHECK(kinds[int(gradients::ParentKind::surface)] > 0);
    CHECK(kinds[int(gradients::ParentKind::medium)] > 0);
    CHECK(kinds[int(gradients::ParentKind::specular)] > 0);
    CHECK(kinds[int(gradients::ParentKind::none)] == 0);
  }
  Config c;
  c.photons = 9000;  // three photon chunks
  c.radius_scale = 0.02;
  integrators::GvpmSettings g;
  g.photons = c.photons;
  g.radius_scale = c.radius_scale;
  g.distance_samples = 4;
  integrators::GvpmIntegrator in(g);
  auto opt = test::quiet_options(3, 21, kBoxDepth);
  opt.threads = 1;
  const auto one = in.render(*s, opt);
  opt.threads = 2;
  const auto two = in.render(*s, opt);
  opt.seed = 22;
  const auto other = in.render(*s, opt);
  REQUIRE(one.stats.get("gvpm.photons_stored") > 0);
  REQUIRE(one.stats.get("gvpm.shift.reconnections") > 0);
  bool same = true, differs = false;
  for (const char* name : {"primal", "dx", "dy", "direct"}) {
    const core::Image &a = layer(one, name), &b = layer(two, name), &o = layer(other, name);
    for (size_t i = 0; i < a.size(); ++i) {
      same = same && (a[i] == b[i]).all();
      differs = differs || !(a[i] == o[i]).all();
    }
  }
  CHECK(same);
  CHECK(differs);
  auto popt = test::quiet_options(4, 21, kBoxDepth);
  popt.raw = true;
  const auto whole = in.render(*s, popt);
  core::RawImage sum;
  for (int k = 0; k < 3; ++k) {
    popt.part = k;
    popt.parts = 3;
    const auto part = in.render(*s, popt);
    if (k == 0) sum = part.raw;
    else sum.add(part.raw);
  }
  CHECK(sum.counts.at("spp") == whole.raw.counts.at("spp"));
  double worst = 0;
  for (const char* name : {"primal", "dx", "dy", "direct"}) {
    const auto& a = sum.sums.at(name);
    const auto& w = whole.raw.sums.at(name);
    for (size_t i = 0; i < w.size(); ++i) worst = std::max(worst, ((a[i] - w[i]).abs() / (w[i].abs() + 1e-300)).maxCoeff());
  }
  CHECK(worst < 1e-12);
}

namespace {
void registry_test(const std::string& name) {
  integrators::Settings settings;
  settings.set("photons", "3000");
  settings.set("radius_scale", "0.02");
  auto in = integrators::make_integrator(name, settings);
  CHECK(in->name() == name);
  {
    const auto s = test::lit_box(nullptr, nullptr, 16);
    const auto r = in->render(*s, test::quiet_options(2, 4, kBoxDepth));
    CHECK(r.stats.get(name + ".photon_passes_skipped") == 2);
    CHECK(r.stats.get(name + ".photon_paths") == 0);
    CHECK(r.stats.get(name + ".primary_segments") + r.stats.get(name + ".shift.attempted") == 0);
  }
  const auto s = test::media_box(true, 16);
  auto opt = test::quiet_options(2, 21, kBoxDepth);
  opt.threads = 1;
  auto one = in->render(*s, opt);
  opt.threads = 2;
  const auto two = in->render(*s, opt);
  REQUIRE(one.stats.get(name + ".gather_points") > 0);
  REQUIRE(one.stats.get(name + ".shift.reconnections") > 0);
  CHECK(one.stats.get("gvpm.gather_points") == 0);
  CHECK(one.info["gather"].dump().find("beam") != std::string::npos);
  if (name == "gbeam") CHECK(one.stats.get("gbeam.beams_stored") > 0);
  bool same = true;
  for (const char* layer_name : {"primal", "dx", "dy", "direct"}) {
    const core::Image &a = layer(one, layer_name), &b = layer(two, layer_name);
    for (size_t i = 0; i < a.size(); ++i) same = same && (a[i] == b[i]).all();
  }
  CHECK(same);
}
}  // namespace

TEST_CASE("gbre and gbeam: from the registry; without media no photon; with media seed-only determinism", "[unit]") {
  registry_test("gbre");
  registry_test("gbeam");
}
