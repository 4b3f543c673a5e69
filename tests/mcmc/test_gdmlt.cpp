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
#include <catch2/catch.hpp>

#include "integrators/gdmlt/gdmlt_integrator.h"
#include "integrators/integrator.h"
#include "mcmc/gradient_target.h"
#include "pathspace/sample_stream.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {
constexpr int kRes = 32, kBlock = 8, kRuns = 10;

integrators::RenderResult render(const scene::Scene& s, const std::string& name, int spp, uint64_t seed,
                                 gradients::JacobianFault fault = gradients::JacobianFault::none) {
  integrators::Settings settings;
  std::unique_ptr<integrators::Integrator> in;
  if (name == "gdmlt") {
    settings.set("bootstrap", "20000");
    integrators::GdmltSettings g = integrators::GdmltSettings::read(settings);
    g.fault = fault;
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
};

Stats run_stats(const scene::Scene& s, const std::string& name, int spp, uint64_t seed0,
                gradients::JacobianFault fault = gradients::JacobianFault::none) {
  const size_t nb = size_t((kRes / kBlock) * (kRes / kBlock));
  Stats st;
  st.image.resize(1 + nb);
  st.gradient.resize(2 * nb);
  for (int r = 0; r < kRuns; ++r) {
    const auto res = render(s, name, spp, seed0 + uint64_t(r), fault);
    const bool gd = name == "gdmlt";
    const core::Image& img = gd ? layer(res, "recon_l2") : res.layers[0].image;
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

void check_against_pt(const scene::Scene& s, uint64_t seed, bool negative_control) {
  const Stats pt = run_stats(s, "path", 64, seed + 5000);
  const Stats gd = run_stats(s, "gdmlt", 128, seed);
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
  const Stats broken = run_stats(s, "gdmlt", 128, seed, gradients::JacobianFault::unit);
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
  mcmc::GradientTarget target(*s, identity, o);
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
      const int64_t p = int64_t(py) * kRes + px, plane = int64_t(kRes) * kRes;
      const bool forward = t.gradient_row == p || t.gradient_row == plane + p;  // neighbour right or below
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
