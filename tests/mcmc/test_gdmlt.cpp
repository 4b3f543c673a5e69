// `--integrator gdmlt` (Manzi et al. 2014 on the extended path space) against the
// reference path tracer. K independent runs of each (fixed seeds); Welch tests (see
// tests/support/welch.h) of
//  * the L2 reconstruction's image mean (alpha = 1%) and its 8x8 block means (Sidak, 1%
//    family-wise): L2 screened Poisson reconstruction is unbiased (Lehtinen et al. 2013);
//  * the dx and dy layers' 8x8 block means against the finite differences of the PT
//    images (E[Delta_ij] = I_j - I_i, Manzi 2014 Eqs. 4-5), Sidak over all blocks;
// on two scenes: a lit box with a rough conductor sphere (reconnection at diffuse and
// glossy-above-threshold vertices) and with a mirror and a glass sphere (specular chains:
// manifold walks). A real defect must be rejected: gdmlt with every shift Jacobian forced
// to 1 (on the first scene). Also: with T_1 = identity the pair sample of every neighbour is exactly
// +-|N_i| times the primal value (the gradients reduce to finite differences).
#include <algorithm>
#include <map>
#include <catch2/catch.hpp>

#include "integrators/gdmlt/gdmlt_integrator.h"
#include "integrators/integrator.h"
#include "kernels_adaptive/pair_kernel.h"
#include "mcmc/gradient_target.h"
#include "pathspace/sample_stream.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 10;

// What gdmlt runs with: its kernel and the deliberate defects of the negative controls.
struct Variant {
  std::string kernel = "standard";
  gradients::JacobianFault fault = gradients::JacobianFault::none;
  bool symmetric_as_one = false;  // symmetric adaptive pairs splatted with weight 1, not 2
  bool incmw = true;
  std::string mutations = "pss";
};

integrators::RenderResult render(const scene::Scene& s, const std::string& name, int spp, uint64_t seed,
                                 const Variant& variant = {}) {
  integrators::Settings settings;
  std::unique_ptr<integrators::Integrator> in;
  if (name == "gdmlt") {
    settings.set("bootstrap", "20000");
    settings.set("kernel", variant.kernel);
    settings.set("incmw", variant.incmw ? "true" : "false");
    settings.set("mutations", variant.mutations);
    integrators::GdmltSettings g = integrators::GdmltSettings::read(settings);
    g.fault = variant.fault;
    g.fault_symmetric_as_one = variant.symmetric_as_one;
    in = std::make_unique<integrators::GdmltIntegrator>(g, settings.to_json());
  } else {
    in = integrators::make_integrator(name, settings);
  }
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = 6;
  opt.quiet = true;
  return in->render(s, opt);
}

const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  FAIL("no layer " << name);
  return r.layers[0].image;
}

// Block means of v(x, y) over 8x8 blocks (x < xmax, y < ymax), appended to out[first..].
template <typename F>
void blocks(F&& v, int xmax, int ymax, std::vector<std::vector<double>>& out, size_t first) {
  const int nb = kRes / kBlock;
  for (int by = 0; by < nb; ++by)
    for (int bx = 0; bx < nb; ++bx) {
      double sum = 0;
      int n = 0;
      for (int y = by * kBlock; y < std::min(ymax, (by + 1) * kBlock); ++y)
        for (int x = bx * kBlock; x < std::min(xmax, (bx + 1) * kBlock); ++x, ++n) sum += v(x, y);
      out[first + size_t(by * nb + bx)].push_back(sum / n);
    }
}

struct Stats {
  std::vector<std::vector<double>> image;     // [0] image mean, [1..] block means
  std::vector<std::vector<double>> gradient;  // dx block means, then dy block means
  std::vector<core::Image> runs;              // each run's image (PT: for the pair rows)
  // kernel=adaptive: per run r, per 8x8 block of the rows' end pixels b, the mean over the
  // block's rows of (gdmlt's I_b - I_a) - (PT run r's I_b - I_a).
  std::vector<std::vector<double>> pair_error;
};

// The pair rows of an adaptive gdmlt render against PT run `pt`: appends one value per
// block to st.pair_error. A non-symmetric pair's one row is unbiased for I_b - I_a. A
// symmetric pair's two rows are not one by one (2 Delta^i_ij and 2 Delta^j_ji: each half
// also carries its own pixel's Omega_bar / T_0 part, Manzi 2014 Eqs. 4-6), only their
// average is: it is compared once, at the pair's smaller pixel index.
void pair_errors(const integrators::RenderResult& res, const core::Image& pt, Stats& st) {
  const size_t nb = size_t(kRes / kBlock);
  std::map<std::pair<int, int>, double> rows;  // (b, a) -> value of the row I_b - I_a (indirect)
  for (int k = 0;; ++k) {
    const std::string name = "pairs." + std::to_string(k);
    if (std::none_of(res.layers.begin(), res.layers.end(), [&](const auto& l) { return l.name == name; })) break;
    const core::Image &value = layer(res, name), &offset = layer(res, name + ".offset");
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x)
        if (offset(x, y).z() != 0.0f) {
          const int a = (y + int(offset(x, y).y())) * kRes + x + int(offset(x, y).x());
          REQUIRE(rows.emplace(std::make_pair(y * kRes + x, a), double(value(x, y).sum())).second);
        }
  }
  REQUIRE(rows.size() >= size_t(kRes * kRes));  // n = 4 partners per pixel
  const core::Image& direct = layer(res, "direct");
  const auto total = [](const core::Image& im, int p) { return double(im[size_t(p)].sum()); };
  std::vector<double> sum(2 * nb * nb, 0.0);
  std::vector<int> count(2 * nb * nb, 0);
  int symmetric = 0;
  for (const auto& [ba, v] : rows) {
    const auto [b, a] = ba;
    const auto reverse = rows.find({a, b});
    if (reverse != rows.end() && b > a) continue;  // counted with its twin
    symmetric += reverse != rows.end();
    const double est = reverse != rows.end() ? 0.5 * (v - reverse->second) : v;
    // Rows hold the indirect part; the direct part's difference is added.
    const double gd = est + total(direct, b) - total(direct, a);
    // Per block, horizontal and vertical pairs apart, each oriented toward increasing
    // pixel index: a biased row scale (the negative control) then adds up instead of
    // cancelling between opposite orientations.
    const bool horizontal = std::abs(b % kRes - a % kRes) >= std::abs(b / kRes - a / kRes);
    const size_t block = (horizontal ? 0 : nb * nb) + size_t(b / kRes / kBlock) * nb + size_t(b % kRes / kBlock);
    sum[block] += (b > a ? 1.0 : -1.0) * (gd - (total(pt, b) - total(pt, a)));
    ++count[block];
  }
  REQUIRE(symmetric > kRes * kRes / 2);  // flat regions: mostly symmetric pairs
  st.pair_error.resize(2 * nb * nb);
  for (size_t b = 0; b < 2 * nb * nb; ++b) st.pair_error[b].push_back(sum[b] / count[b]);
}

Stats run_stats(const scene::Scene& s, const std::string& name, int spp, uint64_t seed0, const Variant& variant = {},
                const Stats* pt = nullptr) {
  const size_t nb = size_t((kRes / kBlock) * (kRes / kBlock));
  Stats st;
  st.image.resize(1 + nb);
  st.gradient.resize(2 * nb);
  for (int r = 0; r < kRuns; ++r) {
    const auto res = render(s, name, spp, seed0 + uint64_t(r), variant);
    const bool gd = name == "gdmlt";
    const core::Image& img = gd ? layer(res, "recon_l2") : res.layers[0].image;
    if (!gd) st.runs.push_back(img);
    double all = 0;
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) all += double(img(x, y).sum());
    st.image[0].push_back(all / (kRes * kRes));
    blocks([&](int x, int y) { return double(img(x, y).sum()); }, kRes, kRes, st.image, 1);
    // Gradients of the indirect part: gdmlt's dx/dy layers; PT: differences of its image
    // (the direct part's differences are added to gdmlt's from its own direct layer).
    const core::Image& base = gd ? layer(res, "direct") : res.layers[0].image;
    auto dx = [&](int x, int y) {
      const double d = double(base(x + 1, y).sum()) - double(base(x, y).sum());
      return gd ? d + double(layer(res, "dx")(x, y).sum()) : d;
    };
    auto dy = [&](int x, int y) {
      const double d = double(base(x, y + 1).sum()) - double(base(x, y).sum());
      return gd ? d + double(layer(res, "dy")(x, y).sum()) : d;
    };
    if (gd && variant.kernel == "adaptive") {
      pair_errors(res, pt->runs[size_t(r)], st);
      continue;
    }
    blocks(dx, kRes - 1, kRes, st.gradient, 0);
    blocks(dy, kRes, kRes - 1, st.gradient, nb);
  }
  return st;
}

std::unique_ptr<scene::Scene> glossy_box() {
  return test::lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                   scene::ConductorFresnel{},
                                                                   scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                       nullptr, kRes);
}
std::unique_ptr<scene::Scene> specular_box() {
  return test::lit_box(scene::make_mirror(scene::constant_texture(Rgb(0.9f, 0.9f, 0.9f))),
                       scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), kRes);
}

void check_against_pt(const scene::Scene& s, uint64_t seed, bool negative_control, const std::string& mutations = "pss") {
  const Stats pt = run_stats(s, "path", 64, seed + 5000);
  Variant variant;
  variant.mutations = mutations;
  const Stats gd = run_stats(s, "gdmlt", 128, seed, variant);  // kernel=standard: the dx/dy layers
  double mean_ratio = 0;
  const double r_img = test::worst_welch(gd.image, pt.image, 0.01, &mean_ratio);
  const test::Moments m = test::moments(gd.image[0]), p = test::moments(pt.image[0]);
  INFO("L2 mean: GD-MLT " << m.mean << " +- " << std::sqrt(m.var / kRuns) << ", PT " << p.mean << " +- "
                          << std::sqrt(p.var / kRuns) << "; mean |t|/crit " << mean_ratio << ", worst block "
                          << r_img);
  CHECK(r_img < 1.0);
  const double r_grad = test::sidak_welch(gd.gradient, pt.gradient, 0.01);
  INFO("dx/dy blocks: worst |t|/crit " << r_grad);
  CHECK(r_grad < 1.0);

  if (!negative_control) return;
  // The same tests reject gdmlt with every shift Jacobian forced to 1 (watched: image
  // worst |t|/crit 1.66, gradients 1.89 on the rough-conductor box; on the mirror/glass
  // box the same defect reaches only 1.2 / 1.03 -- its specular chains' walks and copies
  // carry Jacobians near 1 over most of the image -- so it is not a control there). Power: the L2 image mean's
  // standard error is ~0.14-0.35% of the mean, a block's ~4x that; with the Sidak
  // critical t of ~4, block biases above ~2-6% are detected.
  Variant unit_jacobian = variant;
  unit_jacobian.fault = gradients::JacobianFault::unit;
  const Stats broken = run_stats(s, "gdmlt", 128, seed, unit_jacobian);
  const double rb_img = test::worst_welch(broken.image, pt.image, 0.01);
  const double rb_grad = test::sidak_welch(broken.gradient, pt.gradient, 0.01);
  INFO("Jacobian forced to 1: image worst |t|/crit " << rb_img << ", gradients " << rb_grad);
  CHECK(std::max(rb_img, rb_grad) > 1.0);
}
}  // namespace

TEST_CASE("gdmlt: L2 image and gradients agree with the path tracer (lit box, rough conductor)", "[stat]") {
  check_against_pt(*glossy_box(), 100, true);
}

TEST_CASE("gdmlt: L2 image and gradients agree with the path tracer (mirror and glass: manifold shift)", "[stat]") {
  check_against_pt(*specular_box(), 200, false);
}

// mutations=path (gdmlt_path.h): memlt's mutations on states (x, j), G-BDPT's shift as T_1.
// Negative control as above: every shift Jacobian forced to 1 (watched: see the INFO).
TEST_CASE("gdmlt mutations=path: L2 image and gradients agree with the path tracer (lit box, rough conductor)",
          "[stat]") {
  check_against_pt(*glossy_box(), 400, true, "path");
}

TEST_CASE("gdmlt mutations=path: L2 image and gradients agree with the path tracer (mirror and glass)", "[stat]") {
  check_against_pt(*specular_box(), 500, false, "path");
}

TEST_CASE("gdmlt kernel=adaptive: L2 image and every pair row agree with the path tracer", "[stat]") {
  // The structure-adaptive kernel (Manzi 2014, Sec. 3.5, Algorithm 1): symmetric pairs
  // write 2 Delta^i_ij into their own row, non-symmetric ones Delta^i_ij and -Delta^j_ji
  // into the shared row. Each run's kernel comes from its own feature pass, so the rows
  // are checked run by run: per block, the mean over rows of (gdmlt row - PT run r's
  // I_b - I_a) has mean 0 across runs (one-sample t-test: Welch against exact zeros has
  // K - 1 degrees of freedom), Sidak over the blocks.
  const auto s = glossy_box();
  const Stats pt = run_stats(*s, "path", 64, 305000);
  Variant adaptive;
  adaptive.kernel = "adaptive";
  const Stats gd = run_stats(*s, "gdmlt", 256, 300, adaptive, &pt);
  const std::vector<std::vector<double>> zeros(gd.pair_error.size(), std::vector<double>(kRuns, 0.0));
  double mean_ratio = 0;
  const double r_img = test::worst_welch(gd.image, pt.image, 0.01, &mean_ratio);
  INFO("L2 image: mean |t|/crit " << mean_ratio << ", worst block " << r_img);
  CHECK(r_img < 1.0);
  const double r_rows = test::sidak_welch(gd.pair_error, zeros, 0.01);
  INFO("pair rows: worst block |t|/crit " << r_rows);
  CHECK(r_rows < 1.0);

  // Negative control: symmetric pairs splatted with weight 1 instead of 2 (Algorithm 1
  // line 23 dropped) halve their rows.
  adaptive.symmetric_as_one = true;
  const Stats broken = run_stats(*s, "gdmlt", 256, 300, adaptive, &pt);
  const double rb_rows = test::sidak_welch(broken.pair_error, zeros, 0.01);
  const double rb_img = test::worst_welch(broken.image, pt.image, 0.01);
  INFO("symmetric weight 1: rows " << rb_rows << ", image " << rb_img);
  CHECK(rb_rows > 1.0);
}

TEST_CASE("gdmlt: with T_1 = identity every neighbour's pair sample is +-|N_i| times the primal", "[unit]") {
  // T_0 keeps x in pixel i, so the box filter gives f_j(T_0 x) = 0: x is in Omega_bar_i and
  // the sample is f_i(x) itself (Manzi 2014, Sec. 3.2, last paragraph). Splatted with
  // sign and |N_i| for each neighbour choice, its average over the choices puts exactly
  // -f_i into the forward-difference row of a right/lower neighbour and +f_i into that of
  // a left/upper one: finite differences of the primal. (Without the pixel-filter check
  // the identity offset would count as a shifted pair and the sample would vanish.)
  const auto s = glossy_box();
  const gradients::IdentityShift identity;
  mcmc::GradientTargetOptions o;
  o.walk.max_depth = 6;
  const kernels_adaptive::PairKernel kernel = kernels_adaptive::standard_kernel(kRes, kRes);
  mcmc::GradientTarget target(*s, identity, kernel, o);
  core::Rng rng(3, 4);
  int lit = 0;
  for (int n = 0; n < 3000; ++n) {
    pathspace::PrimarySampleStream stream(rng);
    const mcmc::TargetValue t0 = target.evaluate(stream);  // records the coordinates
    const int px = int(t0.raster.x()), py = int(t0.raster.y());
    const int count = (px > 0) + (px + 1 < kRes) + (py > 0) + (py + 1 < kRes);
    if (is_black(t0.value)) continue;
    ++lit;
    std::vector<int64_t> rows;
    for (int k = 0; k < count; ++k) {
      stream.mutable_samples()[0] = (float(k) + 0.5f) / float(count);
      stream.rewind();
      const mcmc::TargetValue t = target.evaluate(stream);
      REQUIRE((t.value == t0.value).all());
      const int32_t p = py * kRes + px;
      const bool forward = kernel.rows[size_t(t.gradient_row)].i == p;  // row I_j - I_i: neighbour right or below
      for (int c = 0; c < 3; ++c)
        REQUIRE(double(t.gradient[c]) == Approx((forward ? -1.0 : 1.0) * count * double(t.value[c])).epsilon(1e-6));
      rows.push_back(t.gradient_row);
    }
    std::sort(rows.begin(), rows.end());
    REQUIRE(std::unique(rows.begin(), rows.end()) == rows.end());  // every neighbour chosen once
  }
  REQUIRE(lit > 500);
}

TEST_CASE("gdmlt: no manifold walk where the scene has no specular chain; walks where it has", "[unit]") {
  // The manifold shift walks only specular chains (gradients/manifold_shift.h); the
  // rough-conductor box (alpha 0.2, above the 0.05 threshold) has none. The counter is
  // the proof that the machinery is skipped, and the mirror/glass box shows it counts.
  const auto diffuse = render(*glossy_box(), "gdmlt", 4, 1);
  CHECK(diffuse.stats.get("gdmlt.manifold.walks") == 0);
  CHECK(diffuse.stats.get("gdmlt.shift.attempted") > 0);
  const auto specular = render(*specular_box(), "gdmlt", 4, 1);
  CHECK(specular.stats.get("gdmlt.manifold.walks") > 0);
  CHECK(specular.stats.get("gdmlt.nan_dropped") == 0);
}

TEST_CASE("gdmlt: the feature pass runs only for kernel=adaptive, the AO pass only for incmw=true", "[unit]") {
  Variant plain;  // kernel=standard
  plain.incmw = false;
  const auto p = render(*glossy_box(), "gdmlt", 2, 1, plain);
  CHECK(p.stats.get("gdmlt.features.rays") == 0);
  CHECK(p.stats.get("gdmlt.ao.rays") == 0);
  CHECK(p.stats.get("gdmlt.incmw.shifts") == 0);
  for (const auto& l : p.layers) CHECK((l.name != "ao" && l.name.rfind("features.", 0) != 0 && l.name != "pairs.0"));
  Variant full;
  full.kernel = "adaptive";
  const auto f = render(*glossy_box(), "gdmlt", 2, 1, full);
  CHECK(f.stats.get("gdmlt.features.rays") == kRes * kRes * 4);
  CHECK(f.stats.get("gdmlt.ao.rays") == kRes * kRes * 16);
  for (const char* name : {"ao", "features.normal", "features.albedo", "features.depth", "pairs.0", "pairs.0.offset"})
    CHECK(std::any_of(f.layers.begin(), f.layers.end(), [&](const auto& l) { return l.name == name; }));
}
