// The public Mitsuba scenes under ../shared/scenes, or the folder $DP_SHARED_SCENES names
// (absent from a user's clone: then the executable exits with 77 before any assertion,
// which ctest reports as skipped, SKIP_RETURN_CODE in mitsuba_tests.cmake):
//  * [unit] every scene file loads into a committed scene with lights;
//  * [slow] path-traced renders of cornell-box, veach-mis and veach-ajar, and volpath and
//    bdpt renders of volumetric-caustic, are compared with Bitterli's Tungsten references
//    (the [!mayfail] cases document known differences). The scenes are rendered at a
//    reduced resolution (each render pixel = the mean over a factor x factor block of
//    reference pixels, our camera's box filter), K = 16 independent renders give the
//    standard error of every block mean, and each B x B block of render pixels and the
//    image mean are compared with the reference by z = (ours - reference) / standard error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/image_io.h"
#include "integrators/integrator.h"
#include "scene/loaders/loader.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"

using namespace dp;
using namespace dp::scene;
namespace fs = std::filesystem;

namespace {

fs::path shared_scenes() {
  if (const char* env = std::getenv("DP_SHARED_SCENES"); env && *env) return fs::path(env);
  return fs::path(DP_SOURCE_DIR) / ".." / "shared" / "scenes";
}

// Called first in every test case: without the scenes there is nothing to test, and the
// run must not count as a pass (ctest: SKIP_RETURN_CODE 77).
void require_shared_or_skip() {
  if (fs::is_directory(shared_scenes())) return;
  std::printf("SKIPPED: %s is absent (public test scenes are not part of the repository)\n",
              shared_scenes().string().c_str());
  std::fflush(stdout);
  std::exit(77);
}

// K renders estimate each standard error, so under "no bias" a block's z follows
// Student's t with K - 1 degrees of freedom (more for the reference-noise part, whose
// variance comes from many pixels: K - 1 is the heavy-tailed, conservative end).
constexpr int kRenders = 16;

// "Beyond 3 sigma" keeps its meaning, a per-block false-alarm probability of
// p = 0.0027 (the normal's two-sided tail beyond 3): with the estimated standard error
// and three channels per block, a block is beyond when any channel's |z| exceeds the
// t_{K-1} quantile of two-sided tail p / 3 (Bonferroni over R, G, B, whatever their
// correlation): 4.12 for K = 16. (Counting |z| > 3 itself would be p <= 3 x 0.0090.)
constexpr double kBlockFalseAlarm = 0.0027;
double block_threshold() {
  const boost::math::students_t t(double(kRenders - 1));
  return boost::math::quantile(boost::math::complement(t, kBlockFalseAlarm / 3.0 / 2.0));
}

// How many of n independent blocks may be beyond with a family-wise false alarm of 1 %:
// the smallest k with P(X > k) <= 0.01 for X ~ Binomial(n, 0.0027):
//   n = 256 (cornell-box): k = 3 (P(X > 3) = 0.0054, P(X > 2) = 0.033);
//   n = 144 (veach-*):     k = 2 (P(X > 2) = 0.0072, P(X > 1) = 0.058).
int allowed_beyond(int n) {
  const boost::math::binomial bin(double(n), kBlockFalseAlarm);
  int k = 0;
  while (boost::math::cdf(boost::math::complement(bin, double(k))) > 0.01) ++k;
  return k;
}

// Image mean: three channel z values, each within the two-sided t_{K-1} quantile at
// 1 % / 3 (Bonferroni over the channels): |z| <= 3.48 for K = 16.
double mean_z_limit() {
  const boost::math::students_t t(double(kRenders - 1));
  return boost::math::quantile(boost::math::complement(t, 0.01 / 3.0 / 2.0));
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct BlockStats {
  std::string map;  // per block: ratio of luminances ours/reference, '*' where beyond
  int blocks = 0, beyond = 0;
  double max_abs_z = 0;
  Rgbd mean, mean_se, ref_mean;
  Rgbd mean_z() const { return Rgbd((mean - ref_mean).abs() / mean_se.max(1e-12)); }
};

// The assertions shared by the scene comparisons.
void check_agreement(const BlockStats& s) {
  const int allowed = allowed_beyond(s.blocks);
  INFO(s.beyond << " of " << s.blocks << " blocks with |z| > " << block_threshold() << ", " << allowed
                << " allowed (p = " << kBlockFalseAlarm << "); image-mean z (" << s.mean_z()[0] << " "
                << s.mean_z()[1] << " " << s.mean_z()[2] << "), limit " << mean_z_limit());
  CHECK(s.beyond <= allowed);
  CHECK(s.mean_z().maxCoeff() <= mean_z_limit());
}

// A rectangle of render pixels left out of a comparison (w == 0: none).
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool contains(int px, int py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};

// K renders at (w, h); reference box-downsampled by `factor`; blocks of b x b pixels.
// `excluded` (whole blocks) is left out of the block count and of the image mean.
BlockStats compare(const Scene& scene, const core::Image& ref, int factor, int b, int spp, int k, int max_depth,
                   const char* integrator = "path", PixelRect excluded = {},
                   const std::vector<std::pair<std::string, std::string>>& set = {}) {
  const int w = scene.camera().width(), h = scene.camera().height();
  REQUIRE(ref.width() == w * factor);
  REQUIRE(ref.height() == h * factor);
  std::vector<core::Image> renders;
  for (int i = 0; i < k; ++i) {
    integrators::Settings settings;
    for (const auto& [key, value] : set) settings.set(key, value);
    auto integ = integrators::make_integrator(integrator, settings);
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.seed = uint64_t(1000 + i);
    opt.max_depth = max_depth;
    opt.quiet = true;
    renders.push_back(integ->render(scene, opt).layers[0].image);
  }
  core::Image small(w, h);
  for (int y = 0; y < h * factor; ++y)
    for (int x = 0; x < w * factor; ++x) small(x / factor, y / factor) += ref(x, y) / float(factor * factor);
  // Noise of the reference itself: per pixel, r = p - mean of its 4 neighbours has
  // variance 1.25 sigma^2 for independent pixel noise (more where the image has edges,
  // which makes this estimate conservative); a block mean of n pixels has sigma^2 / n.
  core::Image ref_var(w, h);
  for (int y = 1; y + 1 < h * factor; ++y)
    for (int x = 1; x + 1 < w * factor; ++x) {
      const Rgb r = ref(x, y) - 0.25f * (ref(x - 1, y) + ref(x + 1, y) + ref(x, y - 1) + ref(x, y + 1));
      ref_var(x / factor, y / factor) += r * r / 1.25f;
    }
  BlockStats st;
  auto included = [&](int bx, int by, int bw, int bh) {
    int n = 0;
    for (int y = by; y < by + bh; ++y)
      for (int x = bx; x < bx + bw; ++x) n += excluded.contains(x, y) ? 0 : 1;
    return n;
  };
  auto block_mean = [&](const core::Image& img, int bx, int by, int bw, int bh) {
    Rgbd s = Rgbd::Zero();
    for (int y = by; y < by + bh; ++y)
      for (int x = bx; x < bx + bw; ++x)
        if (!excluded.contains(x, y)) s += img(x, y).cast<double>();
    return Rgbd(s / double(included(bx, by, bw, bh)));
  };
  auto z_of = [&](int bx, int by, int bw, int bh, Rgbd& mean, Rgbd& se, Rgbd& refm) {
    Rgbd sum = Rgbd::Zero(), sum2 = Rgbd::Zero();
    for (const core::Image& r : renders) {
      const Rgbd m = block_mean(r, bx, by, bw, bh);
      sum += m;
      sum2 += m * m;
    }
    mean = sum / double(k);
    se = ((sum2 / double(k) - mean * mean).max(0.0) * (double(k) / double(k - 1)) / double(k)).sqrt();
    refm = block_mean(small, bx, by, bw, bh);
    const double n_ref = double(included(bx, by, bw, bh)) * double(factor * factor);
    const Rgbd ref_se2 = block_mean(ref_var, bx, by, bw, bh) / double(factor * factor) / n_ref;
    se = (se * se + ref_se2).sqrt();
    return Rgbd((mean - refm).abs() / se.max(1e-12));
  };
  for (int by = 0; by + b <= h; by += b) {
    for (int bx = 0; bx + b <= w; bx += b) {
      if (included(bx, by, b, b) == 0) {
        st.map += "    -- ";
        continue;
      }
      Rgbd m, se, r;
      const Rgbd z = z_of(bx, by, b, b, m, se, r);
      ++st.blocks;
      if (z.maxCoeff() > block_threshold()) ++st.beyond;
      st.max_abs_z = std::max(st.max_abs_z, z.maxCoeff());
      const double lm = 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2];
      const double lr = 0.2126 * r[0] + 0.7152 * r[1] + 0.0722 * r[2];
      char cell[32];
      std::snprintf(cell, sizeof(cell), " %5.3f%c", lr > 0 ? lm / lr : 0.0, z.maxCoeff() > block_threshold() ? '*' : ' ');
      st.map += cell;
    }
    st.map += "\n";
  }
  z_of(0, 0, w, h, st.mean, st.mean_se, st.ref_mean);
  return st;
}

void report(const std::string& name, const BlockStats& s) {
  std::printf("%s: %d blocks, %d with |z| > %.2f (max %.2f); image mean (%.5f %.5f %.5f) +- (%.5f %.5f %.5f), "
              "reference (%.5f %.5f %.5f), ratio (%.4f %.4f %.4f)\n",
              name.c_str(), s.blocks, s.beyond, block_threshold(), s.max_abs_z, s.mean[0], s.mean[1], s.mean[2], s.mean_se[0], s.mean_se[1],
              s.mean_se[2], s.ref_mean[0], s.ref_mean[1], s.ref_mean[2], s.mean[0] / s.ref_mean[0],
              s.mean[1] / s.ref_mean[1], s.mean[2] / s.ref_mean[2]);
  std::printf("%s", s.map.c_str());
}

// A 1280x720 Bitterli scene rendered at 320x180 (factor 4), 20 x 20 render-pixel
// blocks, at the file's max_depth - 1 (Tungsten's max_bounces; see the veach-ajar test).
BlockStats compare_veach_scene(const std::string& name) {
  const fs::path p = shared_scenes() / name / "scene.xml";
  MitsubaOptions opt;
  opt.parameters = {{"resx", "320"}, {"resy", "180"}};
  const auto scene = load_scene_mitsuba(p.string(), opt);
  const core::Image ref = core::read_exr((shared_scenes() / name / "TungstenRender.exr").string());
  const BlockStats s = compare(*scene, ref, 4, 20, 32, kRenders, scene->integrator_defaults().max_depth - 1);
  report(name, s);
  return s;
}

// The volumetric-caustic scene as its tests render it: v0.6 at 128^2 with an isotropic
// phase (why: the comment of the volpath test below).
std::unique_ptr<Scene> volumetric_caustic_128() {
  const fs::path p = shared_scenes() / "volumetric-caustic" / "scene_v0.6.xml";
  std::string xml = read_text(p);
  xml = std::regex_replace(xml, std::regex("value=\"1024\""), "value=\"128\"");
  xml = std::regex_replace(xml, std::regex("<phase type=\"hg\" >[^<]*<float name=\"g\" value=\"0.5\" />[^<]*</phase>"),
                           "<phase type=\"isotropic\"/>");
  auto scene = load_scene_mitsuba_string(xml, p.string());
  REQUIRE(scene->caps().has_media);
  REQUIRE(scene->media().size() == 1);
  REQUIRE(scene->media()[0].sigma_s[0] == 1.0f);
  REQUIRE(scene->media()[0].phase.type == PhaseFunctionDesc::Type::isotropic);
  REQUIRE(scene->integrator_defaults().type == "volpath");
  return scene;
}

// The depth the volumetric-caustic tests render at: the file's maxDepth 7 minus 2.
//  * minus 1: Bitterli's Mitsuba exports write Tungsten's max_bounces + 1 (the rule of
//    the other Bitterli scenes above), so Tungsten's max_bounces was 6;
//  * minus 1 more: Tungsten counts the index-matched front face of the box as a bounce,
//    deltapath's volpath and bdpt do not ("Index-matched boundaries are not vertices",
//    integrators/volpath/volpath_tracer.h). In tunabrain/tungsten @ 88ea020
//    (src/core/integrators/path_tracer/PathTracer.cpp) the loop increments `bounce` once
//    per iteration, and an iteration that passes a surface through its forward lobe
//    (TraceBase::handleSurface) is an iteration; shadow rays also count each forward
//    crossing (TraceBase::generalizedShadowRayImpl). Mitsuba 0.5's volpath does the same
//    (`rRec.depth++` for a BSDF::ENull sample), so this is the files' depth convention,
//    not only Tungsten's. Every camera path enters the fog through that face exactly once
//    before its first vertex, and nothing outside the box sends light back in, so
//    Tungsten's 6 bounces are 5 of our segments for every path of this scene.
// Measured (bdpt, luminance per 8 x 8 block, image means without the light's block,
// see below): at 5 (512 spp) 251 of the 255 blocks are 0.99-1.01 x the reference, the
// other four lie on the glass ball, where the reference has single-sample fireflies
// (0.80-0.96 x), and the mean is 0.996 x in each channel; at 6 (64 spp), the file's rule
// for the other scenes, the blocks are 1.04-1.56 x (growing away from the light) and
// the mean 1.14-1.16 x; at 4 (64 spp) the blocks are 0.37-0.95 x and the mean 0.80 x.
int volumetric_caustic_depth(const Scene& scene) {
  REQUIRE(scene.integrator_defaults().max_depth == 7);
  return scene.integrator_defaults().max_depth - 2;
}

// The block (render pixels x 56-63, y 8-15) that holds the directly visible light is
// left out of the volumetric-caustic comparisons: the reference is not a rendering of
// the file's emitter there. The light (5 x 4 mm, radiance (541127, 381972, 127324),
// facing down, seen from below at cos 0.138 through 1.04 of fog, T = 0.3535) should add
// E T (solid angle of the light) / (solid angle of a pixel) = (95800, 67600, 22500),
// summed over the reference pixels it covers (in units of one 1024^2 pixel). Our renders
// add (98700, 69700, 23200) (the few % more is the in-scattered glow around it), the
// reference only (17600, 10700, 4200) = 0.16-0.19 x, with the colour 4.1 : 2.5 : 1
// instead of the emitter's 4.25 : 3 : 1. Its brightest pixels sit just above powers of
// two in every channel ((4108, 2088, 1025) and (4108, 2086, 1025)), while the reference's
// single-sample fireflies of the same light seen through the ball elsewhere have the
// emitter's colour exactly ((62.6, 44.2, 14.7), 4.25 : 3 : 1). The emitter's radiance,
// size and the fog are confirmed by the rest of the image, which matches per channel
// (see above), and no renderer setting we know of dims an emitter's directly seen pixels
// and changes their colour while leaving the light it casts unchanged; so this is taken
// to be an artifact of how those few pixels were accumulated or stored in the
// reference, cause unknown. With the block included the image mean is 1.17-1.18 x the
// reference, all of the excess in this one block (3.5 x).
constexpr PixelRect kCausticLightBlock{56, 8, 8, 8};

core::Image read_volumetric_caustic_reference() {
  core::Image ref = core::read_exr((shared_scenes() / "volumetric-caustic" / "TungstenRender.exr").string());
  // The excluded block is the one holding the reference's brightest pixel (the light).
  size_t brightest = 0;
  for (size_t i = 0; i < ref.size(); ++i)
    if (ref[i].sum() > ref[brightest].sum()) brightest = i;
  const int bx = int(brightest % size_t(ref.width())), by = int(brightest / size_t(ref.width()));
  REQUIRE(kCausticLightBlock.contains(bx / 8, by / 8));
  return ref;
}

}  // namespace

TEST_CASE("mitsuba: every shared scene loads", "[unit]") {
  require_shared_or_skip();
  int loaded = 0;
  for (const auto& dir : fs::directory_iterator(shared_scenes())) {
    if (!dir.is_directory()) continue;
    for (const auto& f : fs::directory_iterator(dir.path())) {
      if (f.path().extension() != ".xml") continue;
      INFO(f.path().string());
      std::vector<std::string> warnings;
      MitsubaOptions opt;
      opt.warnings = &warnings;
      std::unique_ptr<Scene> s;
      REQUIRE_NOTHROW(s = load_scene_mitsuba(f.path().string(), opt));
      CHECK(!s->emitters().empty());
      CHECK(!s->shapes().empty());
      CHECK(load_scene(f.path().string()) != nullptr);  // the .xml dispatch
      ++loaded;
    }
  }
  CHECK(loaded >= 15);
}

TEST_CASE("mitsuba: cornell-box agrees with the Tungsten reference", "[slow]") {
  require_shared_or_skip();
  {
    // 1024^2 -> 128^2 (factor 8); 16 x 16 blocks of 8 x 8 render pixels.
    const fs::path p = shared_scenes() / "cornell-box" / "scene_v0.6.xml";
    std::string xml = read_text(p);
    xml = std::regex_replace(xml, std::regex("value=\"1024\""), "value=\"128\"");
    const auto scene = load_scene_mitsuba_string(xml, p.string());
    const core::Image ref = core::read_exr((shared_scenes() / "cornell-box" / "TungstenRender.exr").string());
    // The file's maxDepth 65 is Tungsten's max_bounces 64 + 1 (see veach-ajar below).
    const BlockStats s = compare(*scene, ref, 8, 8, 32, kRenders, scene->integrator_defaults().max_depth - 1);
    report("cornell-box", s);
    check_agreement(s);
  }
}

// Rendered at the file's max_depth - 1: Bitterli's Mitsuba exports write Tungsten's
// max_bounces + 1, and Tungsten's max_bounces = N means N segments, as our max_depth does
// (evidence in docs/mitsuba_import.md). The image mean then agrees to about 0.5 % per channel,
// but the glass teapot's blocks are still +8..+21 % brighter, with no cause found, so
// this case may fail. Session 21 (one 512-spp render each, the upper glass teapot,
// render pixels y 100-123, x 160-191, against the reference: 1.244 x): face normals instead
// of the PLYs' vertex normals 1.244 x (no change); without the 1 / eta^2 radiance scaling
// of refraction (Tungsten's DielectricBsdf has none; it only differs where crossings do
// not pair up, e.g. where the lid overlaps the body: both are closed meshes and their
// bounds overlap in y) 1.198 x; at max_depth 10 / 11 / 12: 1.094 / 1.217 / 1.244 x while
// the image mean goes 0.96 / 0.98 / 1.00 x, so the excess sits in paths of more than 10
// segments. bdpt (128 spp) gives the same 1.242 x: our two estimators agree, so the
// difference is in what both read (geometry, BSDFs, depth convention), not in PT.
TEST_CASE("mitsuba: veach-ajar agrees with the Tungsten reference", "[slow][!mayfail]") {
  require_shared_or_skip();
  const BlockStats s = compare_veach_scene("veach-ajar");
  check_agreement(s);
}

// The same depth rule: veach-mis's file asks for 3 segments, Tungsten rendered 2 (direct
// light only); at the file's 3 the extra bounce put 126 of 144 blocks off.
TEST_CASE("mitsuba: veach-mis agrees with the Tungsten reference", "[slow]") {
  require_shared_or_skip();
  const BlockStats s = compare_veach_scene("veach-mis");
  check_agreement(s);
}

// Participating media (issue 15): the volumetric caustic (a glass ball focusing a tiny
// light, 5 x 4 mm, through an albedo-1 fog filling a Cornell box) rendered by `volpath`
// (which `path` delegates to on a scene with media) at 128^2 against the Tungsten
// reference: the image mean within 1% per channel and the blocks as the other scenes.
// None of the shared files is Tungsten's scene exactly: scene_v3.xml (Mitsuba 3's gallery,
// sigma_t 0.5) fills a cube around the box, so the reference's black frame is foggy;
// scene_v0.6.xml keeps the fog inside the box (an index-matched front face) but was edited
// to HG g = 0.5 (the repository's own earlier copy of the file, zhiwei-c/Monte-Carlo-
// Path-Tracing @ 1314c0f archive/resources/scene/volumetric-caustic/scene_v0.6.xml, has
// no phase element, i.e. isotropic, and is otherwise the same apart from resolution and
// sample count; public Tungsten-format copies have sigma_s 1, isotropic). So this renders
// v0.6 with an isotropic phase, at max_depth 5 (volumetric_caustic_depth: Tungsten counts
// the front face as a bounce) and without the block of the directly visible light (the
// reference is not a rendering of the emitter there: kCausticLightBlock). With these the
// bdpt case below agrees. volpath reaches the caustic's fog and floor, which the glass ball
// hides from plain next-event estimation, by manifold NEE (integrators/volpath/
// volpath_mnee.h; the straight family on by default, the shape families set here).
// Measured (16 renders x 16 spp, 2 cores):
//  * without MNEE: image mean 0.936 x the reference (z 15), 72 of 255 blocks beyond, the
//    caustic's blocks 0.19-0.90 x (only the rare phase or BSDF samples that refract onto
//    the 5 x 4 mm light find it; one render at 2048 spp gives the same 0.94 x);
//  * MNEE along the straight segment, one seed: 0.970 x, 34 beyond, the caustic's blocks
//    0.53-0.75 x (a ball lens has up to three solutions per x and y inside its caustic;
//    the straight seed finds one, or none);
//  * five seeds across the ball (the default): 0.986 x, 13 beyond, caustic blocks
//    0.84-1.12 x;
//  * plus the shape families (a reflection off the ball, two refractions through it where
//    the straight segment misses it; this test, 300 s): 0.9906 x, 8 beyond (max |z| 5.74,
//    3 allowed); with nine seeds 0.9913 x, 7 beyond; refraction - internal reflection -
//    refraction chains (tried, not kept) changed it by < 0.1 %;
//  * at 64 spp (five seeds, reflections only): 0.990 x with the image mean's z about 4:
//    volpath is about 0.7 % below bdpt (0.9975 x), with its low blocks (0.92-0.95 x) spread
//    over the upper walls and the fog. Either a transport MNEE does not reach, or heavy
//    tails (the sample mean of a heavy-tailed estimator is usually low and its estimated
//    variance too small); not resolved. With the light 10 x 10 larger at the same power,
//    volpath with MNEE is 0.9963 x bdpt (z -0.24, 256 spp each).
// Session 20: the fireflies were medium NEE samples 1-4 cm below the light (up to 250 x a
// typical pixel; eight 32-spp renders' image means scattered over 0.974-1.047), which
// equiangular NEE (volpath_equiangular.cpp, on by default) removes (0.983-1.000); and MNEE
// now also reaches the light from behind its plane (the ball's reflection onto the
// ceiling; +0.04 %). This test: 0.9920 x, 4 of 255 blocks beyond (max |z| 5.09, 3
// allowed), image-mean z 3.9 (limit 3.48). Against bdpt (24 x 32 spp vs 16 x 256 spp):
// 0.9979 x (z -2.0), no block pattern; bdpt's own mean is 0.9964 x the reference, z -2.6
// with the reference's noise alone (bench/RESULTS.md). Extra seeds (33, 129) add 0.10 %,
// more walk iterations nothing, more reflection seeds nothing. The blocks beyond are the
// caustic's (its floor spot and cone: 0.945-0.965 x where bdpt is 0.999 x the reference),
// and there volpath's pixels still scatter by +-20 % at 768 spp: MNEE's D grows without
// bound at the caustic's folds, so its block means are heavy-tailed and their standard
// errors too small (bdpt reaches the caustic by light tracing instead).
// Session 21: MNEE seeds from a scan (volpath_mnee_scan.cpp: every isolated solution, a third
// less time; this test 155 s instead of 300 s) leave it as it was: 0.9923 x, 4 of 255
// beyond (max |z| 5.08), image-mean z 3.67. Without the ball (fog, walls and light only)
// volpath is 1.0001 x bdpt (z 0.1, 16 x 32 spp against 16 x 128 spp), no block beyond: the
// deficit comes with the ball. Twice the samples (16 x 32 spp, this test's statistics
// recomputed) give 5 beyond and z 3.75, so it is not noise that more samples remove soon.
// Why: MIS bounds MNEE's contribution at a fold only where p_B = p_x D exceeds p_L; the
// 5 x 4 mm light has p_L = 1 / area = 5e4, so with an isotropic phase (p_x = 1 / 4 pi)
// the bound sets in at D ~ 6e5 (D ~ 1 away from the caustic). The caustic's light,
// re-scattered, is heavy-tailed for every vertex that sees it; bdpt reaches it by light
// tracing and passes (below).
// Session 22: against bdpt at max_depth 4 (the caustic seen directly) volpath was 0.9996 x
// (z -0.25, 40 x 16 spp against 40 x 32 spp) but at max_depth 5 (the caustic lit again
// once) 0.9952 x (z -3.1, 18 renders): MNEE's estimates from every vertex that sees the
// caustic were heavy-tailed. volpath now also traces one light path per camera sample
// through the glass and joins it to the camera and to each camera-path vertex, MIS-weighted
// with MNEE and BSDF sampling (integrators/volpath/volpath_light.cpp, `light_tracing`,
// set here; +6 % time): at max_depth 5 0.9979 x bdpt (z -0.94, 16 renders), and this test
// 0.9954-0.9959 x the reference, 2 of 255 blocks beyond (max |z| 4.26), 199 s.
TEST_CASE("mitsuba: volumetric-caustic agrees with the Tungsten reference (volpath)", "[slow]") {
  require_shared_or_skip();
  const auto scene = volumetric_caustic_128();
  const core::Image ref = read_volumetric_caustic_reference();
  const BlockStats s = compare(*scene, ref, 8, 8, 16, kRenders, volumetric_caustic_depth(*scene), "volpath",
                               kCausticLightBlock, {{"mnee_shapes", "true"}, {"light_tracing", "true"}});
  report("volumetric-caustic", s);
  for (int c = 0; c < 3; ++c) CHECK(std::abs(s.mean[c] / s.ref_mean[c] - 1.0) < 0.01);
  check_agreement(s);
}

// The same with bdpt, which reaches the caustic by light tracing through the glass
// (light -> glass -> medium or floor vertex -> camera). Measured (16 x 16 spp): image mean
// (0.9975, 0.9974, 0.9972) x the reference, z 1.7-2.0 of the limit 3.48, 0 of 255 blocks
// beyond 4.12 (max |z| 3.55); the lowest blocks are the glass ball's (0.82-0.96 x), where
// the reference has single-sample fireflies of the light seen through the ball. Before
// the two corrections above (depth 6 and the light's block included) the mean was 1.33 x
// (1.04-1.55 x in the smooth blocks): one extra bounce and the light's block made it.
TEST_CASE("mitsuba: volumetric-caustic agrees with the Tungsten reference (bdpt)", "[slow]") {
  require_shared_or_skip();
  const auto scene = volumetric_caustic_128();
  const core::Image ref = read_volumetric_caustic_reference();
  const BlockStats s = compare(*scene, ref, 8, 8, 16, kRenders, volumetric_caustic_depth(*scene), "bdpt",
                               kCausticLightBlock);
  report("volumetric-caustic (bdpt)", s);
  for (int c = 0; c < 3; ++c) CHECK(std::abs(s.mean[c] / s.ref_mean[c] - 1.0) < 0.01);
  check_agreement(s);
}
