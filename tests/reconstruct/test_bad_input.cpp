// Bad input: typed errors for what a user can get wrong; NaN/Inf counted, never propagated.
#include <catch2/catch.hpp>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "helpers.h"
#include "reconstruct/render_io.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

Problem good_problem(int w = 12, int h = 9) {
  const core::Image truth = test_image(w, h);
  Problem p;
  p.kernel = Kernel::forward_differences(w, h);
  p.primal = truth;
  p.b = apply_kernel(p.kernel, truth);
  return p;
}

bool all_finite(const core::Image& img) { return img.count_nonfinite() == 0; }

}  // namespace

TEST_CASE("inconsistent problems throw dp::ValueError", "[unit]") {
  CHECK_NOTHROW(validate(good_problem()));
  Problem p = good_problem();
  p.primal = core::Image(11, 9);
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  CHECK_THROWS_AS(solve_l1(p), ValueError);
  p = good_problem();
  p.b.pop_back();
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  for (const float a : {0.0f, -0.2f, std::numeric_limits<float>::quiet_NaN(), kInfinity}) {
    p = good_problem();
    p.alpha = a;
    CHECK_THROWS_AS(solve_l2(p), ValueError);
    CHECK_THROWS_AS(solve_l1(p), ValueError);
  }
  p = good_problem();
  p.row_weights.assign(p.kernel.rows(), 1.0f);
  p.row_weights[3] = -1.0f;
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  p.row_weights.pop_back();
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  p = good_problem();
  p.pixel_weights.assign(p.kernel.pixels(), 1.0f);
  p.pixel_weights[0] = 0.0f;
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  p.pixel_weights[0] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_AS(solve_l2(p), ValueError);
  // Kernels: out-of-range pairs and self pairs.
  CHECK_THROWS_AS(Kernel(4, 4, {{0, 16}}), ValueError);
  CHECK_THROWS_AS(Kernel(4, 4, {{-1, 2}}), ValueError);
  CHECK_THROWS_AS(Kernel(4, 4, {{5, 5}}), ValueError);
  CHECK_THROWS_AS(Kernel(0, 4, {}), ValueError);
  // Grid problems from images of different sizes.
  CHECK_THROWS_AS(make_grid_problem(core::Image(8, 8), core::Image(8, 8), core::Image(8, 7)), ValueError);
  CHECK_THROWS_AS(make_grid_problem(core::Image(), core::Image(), core::Image()), ValueError);
  // The direct solver only applies to the unweighted grid.
  core::Rng rng(1, 1);
  p = good_problem();
  p.kernel = random_kernel(12, 9, 2, rng);
  p.b.assign(p.kernel.rows(), Rgb::Zero());
  SolveOptions direct;
  direct.method = L2Method::direct;
  CHECK_THROWS_AS(solve_l2(p, direct), ValueError);
  p = good_problem();
  p.row_weights.assign(p.kernel.rows(), 2.0f);
  CHECK_THROWS_AS(solve_l2(p, direct), ValueError);
  SolveOptions neg;
  neg.reweightings = -1;
  CHECK_THROWS_AS(solve_l1(good_problem(), neg), ValueError);
}

TEST_CASE("make_grid_problem maps dx/dy images to the forward-difference rows", "[unit]") {
  const core::Image truth = test_image(9, 7);
  core::Image dx(9, 7), dy(9, 7);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) {
      // Last column / row hold garbage that must be ignored.
      dx(x, y) = x + 1 < 9 ? Rgb(truth(x + 1, y) - truth(x, y)) : Rgb::Constant(1e9f);
      dy(x, y) = y + 1 < 7 ? Rgb(truth(x, y + 1) - truth(x, y)) : Rgb::Constant(-1e9f);
    }
  const Problem p = make_grid_problem(truth, dx, dy, 0.3f);
  const std::vector<Rgb> hb = apply_kernel(p.kernel, truth);
  for (size_t r = 0; r < hb.size(); ++r) CHECK(((hb[r] - p.b[r]).abs() < 1e-6f).all());
  CHECK(max_abs_diff(solve_l2(p).image, truth) < 1e-5);
}

TEST_CASE("NaN/Inf inputs are counted and never reach the output", "[unit]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const core::Image truth = test_image(20, 16);
  for (const bool adaptive : {false, true}) {
    core::Rng rng(5, 5);
    Problem p;
    p.kernel = adaptive ? random_kernel(20, 16, 3, rng) : Kernel::forward_differences(20, 16);
    p.primal = truth;
    p.b = apply_kernel(p.kernel, truth);
    p.primal(3, 4) = Rgb(nan, 0.0f, 0.0f);
    p.primal(10, 10) = Rgb(kInfinity, kInfinity, 1.0f);
    p.b[7] = Rgb(0.0f, -kInfinity, 0.0f);
    p.b[30] = Rgb(nan, nan, nan);
    for (const bool l1 : {false, true}) {
      // Tight inner CG so that this checks the NaN policy, not IRLS convergence.
      SolveOptions o;
      o.irls_cg_tolerance = 1e-6;
      const SolveResult r = l1 ? solve_l1(p, o) : solve_l2(p, o);
      INFO((adaptive ? "adaptive " : "grid ") << (l1 ? "L1" : "L2") << " via " << r.method);
      CHECK(r.input.nonfinite_primal_pixels == 2);
      CHECK(r.input.nonfinite_rows == 2);
      CHECK(r.input.anchored_pixels == 0);
      CHECK(all_finite(r.image));
      // Exact gradients elsewhere pin the dropped pixels to the truth.
      CHECK(max_abs_diff(r.image, truth) < 1e-4);
    }
  }
  // A pixel with a NaN primal and no usable rows is anchored to 0, not left singular.
  Problem p;
  p.kernel = Kernel(3, 1, {{0, 1}, {1, 2}});
  p.primal = core::Image(3, 1, Rgb::Constant(0.5f));
  p.primal(2, 0) = Rgb::Constant(nan);
  p.b = {Rgb::Zero(), Rgb::Constant(nan)};
  const SolveResult r = solve_l2(p);
  CHECK(r.input.anchored_pixels == 1);
  CHECK(all_finite(r.image));
  CHECK(r.image(2, 0).abs().maxCoeff() < 1e-6f);
  CHECK((r.image(0, 0) - 0.5f).abs().maxCoeff() < 1e-6f);
  CHECK((r.image(1, 0) - 0.5f).abs().maxCoeff() < 1e-6f);
}

TEST_CASE("gradient renders with missing layers or bad sizes are rejected", "[unit]") {
  const auto dir = std::filesystem::temp_directory_path() / "dp_test_reconstruct";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "render.exr").string();
  const core::Image a(6, 5, Rgb::Constant(0.5f)), small(5, 5);
    core::write_exr(path, {{"primal", a}, {"dx", a}});
  CHECK_THROWS_AS(read_gradient_render(path), IoError);
  // (One EXR cannot hold layers of different sizes; separate files can.)
  const std::string pa = (dir / "p.exr").string(), ps = (dir / "s.exr").string();
  core::write_exr(pa, a);
  core::write_exr(ps, small);
  CHECK_THROWS_AS(read_gradient_images(pa, pa, ps), ValueError);
  CHECK_NOTHROW(read_gradient_images(pa, pa, pa));
  core::write_exr(path, {{"primal", a}, {"dx", a}, {"dy", a}, {"direct", a}});
  const GradientImages g = read_gradient_render(path);
  CHECK(g.direct.has_value());
  CHECK(g.primal.width() == 6);
  CHECK_THROWS_AS(read_gradient_render((dir / "missing.exr").string()), IoError);
  std::filesystem::remove_all(dir);
}
