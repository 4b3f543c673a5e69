// GridOperator::reweight_start (issue 18): the fused IRLS reweighting and CG start
// against set_irls_weights + rhs + an explicit residual, its independence of the thread
// count, mg_pcg from that start, and solve_l1's thread-count independence.
#include <catch2/catch.hpp>

#include <atomic>

#include "helpers.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/multigrid.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

std::vector<Vec4> random_image(size_t n, core::Rng& rng) {
  std::vector<Vec4> v(n);
  for (auto& x : v) x = Vec4{rng.uniform() - 0.5f, rng.uniform(), 2.0f * rng.uniform() - 1.0f, 0.0f};
  return v;
}

// The fused start's outputs.
struct Start {
  std::vector<Vec4> r, z;
  std::vector<Vec4d> rr, bb;
  double total = 0.0;
};

Start fused_start(GridOperator& A, const std::vector<Vec4>& x, const std::vector<Rgb>& b, const std::vector<Vec4>& g,
                  double reg, float alpha, const float* ur, const float* up, int threads) {
  Start s;
  s.r.resize(x.size());
  s.z.resize(x.size());
  s.rr.resize(size_t(A.height()));
  s.bb.resize(size_t(A.height()));
  s.total = A.reweight_start(x.data(), b, g.data(), reg, alpha, ur, up, s.r.data(), s.z.data(), s.rr.data(),
                             s.bb.data(), threads);
  return s;
}

// (A x)_i of the grid operator from its arrays, in double, channel c.
double apply_at(const GridOperator& A, const std::vector<Vec4>& x, int px, int py, int c) {
  const int w = A.width();
  const size_t i = size_t(py) * size_t(w) + size_t(px);
  double a = double(A.diagonal()[i]) * double(x[i][c]);
  if (px + 1 < w) a -= double(A.weights_x()[i]) * double(x[i + 1][c]);
  if (px > 0) a -= double(A.weights_x()[i - 1]) * double(x[i - 1][c]);
  if (py + 1 < A.height()) a -= double(A.weights_y()[i]) * double(x[i + size_t(w)][c]);
  if (py > 0) a -= double(A.weights_y()[i - size_t(w)]) * double(x[i - size_t(w)][c]);
  return a;
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-30); }

}  // namespace

TEST_CASE("fused IRLS reweighting equals set_irls_weights up to the normalization, with r = rhs - A x", "[unit]") {
  core::Rng rng(18, 1);
  const int w = 31, h = 53;
  const Kernel k = Kernel::forward_differences(w, h);
  const std::vector<Vec4> x = random_image(k.pixels(), rng), g = random_image(k.pixels(), rng);
  std::vector<Rgb> b(k.rows());
  for (auto& v : b) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  std::vector<float> user_rows(k.rows()), user_pixels(k.pixels());
  for (float& v : user_rows) v = 0.5f + rng.uniform();
  for (float& v : user_pixels) v = 0.5f + rng.uniform();
  const double reg = 0.05 * std::pow(0.5, 4);
  const float alpha = 0.2f;
  for (const bool user : {false, true}) {
    INFO("user weights " << user);
    const float* ur = user ? user_rows.data() : nullptr;
    const float* up = user ? user_pixels.data() : nullptr;
    GridOperator ref(w, h);
    const double ref_total = ref.set_irls_weights(x.data(), b, g.data(), reg, alpha, ur, up, 1);
    std::vector<Vec4> ref_rhs(k.pixels());
    ref.rhs(b, g.data(), ref_rhs.data(), 1);
    GridOperator A(w, h);
    const Start s = fused_start(A, x, b, g, reg, alpha, ur, up, 1);
    CHECK(rel(s.total, ref_total) < 1e-12);
    // The normalization ref = scale * fused, scale = rows / sum of raw weights.
    const double scale = double(k.rows() + k.pixels()) / s.total;
    double worst_w = 0.0, worst_r = 0.0, worst_rhs = 0.0;
    Vec4d rr, bb;
    std::vector<Vec4d> row_rr(static_cast<size_t>(h)), row_bb(static_cast<size_t>(h));
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        const size_t i = size_t(py) * size_t(w) + size_t(px);
        for (const auto& [f, e] : {std::pair{A.weights_x(), ref.weights_x()}, std::pair{A.weights_y(), ref.weights_y()},
                                   std::pair{A.data_weights(), ref.data_weights()},
                                   std::pair{A.diagonal(), ref.diagonal()}})
          worst_w = std::max(worst_w, std::abs(scale * double(f[i]) - double(e[i])) / std::max(double(e[i]), 1e-3));
        REQUIRE(A.inverse_diagonal()[i] == 1.0f / A.diagonal()[i]);
        Vec4 expect_r = {};
        for (int c = 0; c < 3; ++c) {
          // rhs of the unnormalized system = ref rhs / scale.
          const double rhs = double(ref_rhs[i][c]) / scale;
          worst_rhs = std::max(worst_rhs, std::abs(rhs));
          expect_r[c] = float(rhs - apply_at(A, x, px, py, c));
          worst_r = std::max(worst_r, std::abs(double(s.r[i][c]) - double(expect_r[c])));
        }
        REQUIRE(s.r[i][3] == 0.0f);
        // z: the red half-step r / d on (x + y) even, 0 on odd.
        const Vec4 expect_z = ((px + py) & 1) ? Vec4{} : s.r[i] * A.inverse_diagonal()[i];
        for (int c = 0; c < 4; ++c) REQUIRE(s.z[i][c] == expect_z[c]);
        accumulate(row_rr[size_t(py)], s.r[i] * s.r[i]);
        Vec4 rhs4 = ref_rhs[i] * float(1.0 / scale);
        accumulate(row_bb[size_t(py)], rhs4 * rhs4);
      }
    INFO("weights rel " << worst_w << ", residual abs " << worst_r << " (rhs up to " << worst_rhs << ")");
    CHECK(worst_w < 1e-5);
    CHECK(worst_r < 1e-5 * worst_rhs);
    for (int py = 0; py < h; ++py)
      for (int c = 0; c < 3; ++c) {
        CHECK(rel(s.rr[size_t(py)][c], row_rr[size_t(py)][c]) < 1e-5);
        CHECK(rel(s.bb[size_t(py)][c], row_bb[size_t(py)][c]) < 1e-5);
        CHECK(s.rr[size_t(py)][3] == 0.0);
      }
  }
}

TEST_CASE("fused IRLS reweighting gives bitwise identical results for 1, 2 and 3 threads", "[unit]") {
  core::Rng rng(18, 2);
  const int w = 40, h = 23;
  const Kernel k = Kernel::forward_differences(w, h);
  const std::vector<Vec4> x = random_image(k.pixels(), rng), g = random_image(k.pixels(), rng);
  std::vector<Rgb> b(k.rows());
  for (auto& v : b) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  std::vector<float> user_rows(k.rows());
  for (float& v : user_rows) v = 0.5f + rng.uniform();
  GridOperator A1(w, h);
  const Start s1 = fused_start(A1, x, b, g, 1e-3, 0.2f, user_rows.data(), nullptr, 1);
  for (const int threads : {2, 3}) {
    INFO(threads << " threads");
    GridOperator A(w, h);
    const Start s = fused_start(A, x, b, g, 1e-3, 0.2f, user_rows.data(), nullptr, threads);
    CHECK(s.total == s1.total);
    for (size_t i = 0; i < k.pixels(); ++i) {
      REQUIRE(A.weights_x()[i] == A1.weights_x()[i]);
      REQUIRE(A.weights_y()[i] == A1.weights_y()[i]);
      REQUIRE(A.diagonal()[i] == A1.diagonal()[i]);
      for (int c = 0; c < 4; ++c) {
        REQUIRE(s.r[i][c] == s1.r[i][c]);
        REQUIRE(s.z[i][c] == s1.z[i][c]);
      }
    }
    for (size_t y = 0; y < size_t(h); ++y)
      for (int c = 0; c < 4; ++c) {
        REQUIRE(s.rr[y][c] == s1.rr[y][c]);
        REQUIRE(s.bb[y][c] == s1.bb[y][c]);
      }
  }
}

TEST_CASE("mg_pcg from a fused start solves the reweighted system", "[unit]") {
  core::Rng rng(18, 3);
  const int w = 23, h = 17;
  const Kernel k = Kernel::forward_differences(w, h);
  const std::vector<Vec4> x0 = random_image(k.pixels(), rng), g = random_image(k.pixels(), rng);
  std::vector<Rgb> b(k.rows());
  for (auto& v : b) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  const float alpha = 0.2f;
  GridOperator A(w, h);
  const Start s = fused_start(A, x0, b, g, 1e-3, alpha, nullptr, nullptr, 2);
  // The same system as a Problem (row weights in kernel order, alpha^2 p_i = data term),
  // solved densely.
  Problem p;
  p.kernel = k;
  p.alpha = alpha;
  p.b = b;
  p.primal = core::Image(w, h);
  p.row_weights.resize(k.rows());
  p.pixel_weights.resize(k.pixels());
  for (int y = 0; y < h; ++y)
    for (int px = 0; px < w; ++px) {
      const size_t i = size_t(y) * size_t(w) + size_t(px);
      p.primal[i] = to_rgb(g[i]);
      p.pixel_weights[i] = float(double(A.data_weights()[i]) / (double(alpha) * double(alpha)));
      if (px + 1 < w) p.row_weights[k.grid_dx_row(px, y)] = A.weights_x()[i];
      if (y + 1 < h) p.row_weights[k.grid_dy_row(px, y)] = A.weights_y()[i];
    }
  const core::Image exact = dense_solve(p);
  GridMultigrid M;
  M.coarsest_pixels = 8;
  M.serial_pixels = 16;
  M.build(A, 2);
  CgSettings cg;
  cg.tolerance = 1e-6;
  cg.threads = 2;
  cg.max_iterations = 100;
  std::vector<Vec4> fused = x0;
  CgWorkspace ws;
  ws.r = s.r;
  ws.z = s.z;
  const CgStart start{s.rr.data(), s.bb.data()};
  const CgStats f = mg_pcg(A, M, nullptr, fused.data(), cg, &ws, &start);
  double err = 0.0, mag = 0.0;
  for (size_t i = 0; i < k.pixels(); ++i)
    for (int c = 0; c < 3; ++c) {
      err = std::max(err, std::abs(double(fused[i][c]) - double(exact[i][c])));
      mag = std::max(mag, std::abs(double(exact[i][c])));
    }
  INFO("iterations " << f.iterations << ", residual " << f.relative_residual << ", max error " << err);
  CHECK(f.converged);
  CHECK(f.iterations <= 20);
  CHECK(err < 2e-5 * std::max(1.0, mag));
}

TEST_CASE("solve_l1 on the grid gives bitwise identical images for 1 and 2 threads", "[unit]") {
  core::Rng rng(18, 4);
  const int w = 160, h = 120;
  Problem p;
  p.kernel = Kernel::forward_differences(w, h);
  p.primal = test_image(w, h);
  for (auto& v : p.primal.pixels())
    for (int c = 0; c < 3; ++c) v[c] += float(0.2 * gaussian(rng));
  p.b = apply_kernel(p.kernel, test_image(w, h));
  for (auto& v : p.b)
    for (int c = 0; c < 3; ++c) v[c] += float(0.05 * gaussian(rng));
  std::vector<SolveResult> out;
  for (const int threads : {1, 2}) {
    SolveOptions o;
    o.threads = threads;
    out.push_back(solve_l1(p, o));
  }
  CHECK(out[0].cg_iterations == out[1].cg_iterations);
  for (size_t i = 0; i < out[0].image.size(); ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(out[0].image[i][c] == out[1].image[i][c]);
}

TEST_CASE("solve_l1 with the stop flag set returns its L2 start, marked interrupted", "[unit]") {
  // Interrupts (issue 18): a SIGINT/SIGTERM during reconstruction sets the flag; the solve
  // must end before its next reweighting with a complete image, not run all 20.
  core::Rng rng(18, 5);
  const int w = 64, h = 48;
  Problem p;
  p.kernel = Kernel::forward_differences(w, h);
  p.primal = test_image(w, h);
  p.b = apply_kernel(p.kernel, test_image(w, h));
  for (auto& v : p.b)
    for (int c = 0; c < 3; ++c) v[c] += float(0.3 * gaussian(rng));
  const SolveResult l2 = solve_l2(p);
  const SolveResult full = solve_l1(p);
  std::atomic<bool> stop{true};
  SolveOptions o;
  o.stop = &stop;
  const SolveResult cut = solve_l1(p, o);
  CHECK_FALSE(full.interrupted);
  CHECK(full.reweightings == 20);
  CHECK(cut.interrupted);
  CHECK(cut.reweightings == 0);
  double diff_full = 0.0;
  for (size_t i = 0; i < l2.image.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      REQUIRE(cut.image[i][c] == l2.image[i][c]);  // the same DCT solve (IRLS iteration 0)
      diff_full = std::max(diff_full, double(std::abs(full.image[i][c] - l2.image[i][c])));
    }
  CHECK(diff_full > 1e-3);  // the reweightings do change the image: the check above can fail
}
