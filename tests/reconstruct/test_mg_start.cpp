// The CG start of solve_l1's grid IRLS (issue 18, third round): reweight_start without
// z (the first V-cycle forms its own first red half-step) and runs that start converged
// (no hierarchy built for them) give bitwise the results of the earlier path: z written
// by reweight_start, the hierarchy built for every reweighting.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "helpers.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/multigrid.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

Problem noisy_problem(int w, int h, core::Rng& rng) {
  Problem p;
  p.kernel = Kernel::forward_differences(w, h);
  p.primal = test_image(w, h);
  for (auto& v : p.primal.pixels())
    for (int c = 0; c < 3; ++c) v[c] += float(0.2 * gaussian(rng));
  p.b = apply_kernel(p.kernel, test_image(w, h));
  for (size_t r = 0; r < p.b.size(); ++r) {
    for (int c = 0; c < 3; ++c) p.b[r][c] += float(0.05 * gaussian(rng));
    if (r % 97 == 0) p.b[r] += Rgb(2.0f, -1.5f, 3.0f);  // outliers
  }
  p.alpha = 0.2f;
  return p;
}

// The grid IRLS loop as solve_l1 ran it before: reweight_start writes z, the hierarchy
// is built for every reweighting, mg_pcg takes the given z.
struct Reference {
  core::Image image;
  int cg_iterations = 0;
  double relative_residual = 0.0;
};
Reference reference_l1(const Problem& p, int threads) {
  const int w = p.kernel.width(), h = p.kernel.height();
  const size_t n = p.kernel.pixels();
  SolveOptions direct;
  direct.threads = threads;
  direct.method = L2Method::direct;
  const core::Image l2 = solve_l2(p, direct).image;
  std::vector<Vec4> x(n), g(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = to_vec4(l2[i]);
    g[i] = to_vec4(p.primal[i]);
  }
  GridOperator A(w, h);
  A.set_factor_preconditioner(false);
  GridMultigrid M;
  CgWorkspace ws;
  ws.r.resize(n);
  ws.z.resize(n);
  std::vector<Vec4d> rr(static_cast<size_t>(h)), bb(static_cast<size_t>(h));
  const SolveOptions o;
  Reference out;
  for (int it = 1; it <= o.reweightings; ++it) {
    const double reg = 0.05 * std::pow(0.5, it - 1);
    A.reweight_start(x.data(), p.b, g.data(), reg, p.alpha, nullptr, nullptr, ws.r.data(), ws.z.data(), rr.data(),
                     bb.data(), threads);
    M.build(A, threads);
    CgSettings s;
    s.max_iterations = o.irls_cg_iterations;
    s.tolerance = o.irls_cg_tolerance;
    s.threads = threads;
    const CgStart start{rr.data(), bb.data()};
    const CgStats st = mg_pcg(A, M, nullptr, x.data(), s, &ws, &start);
    out.cg_iterations += st.iterations;
    out.relative_residual = st.relative_residual;
  }
  out.image = core::Image(w, h);
  for (size_t i = 0; i < n; ++i) out.image[i] = to_rgb(x[i]);
  return out;
}

}  // namespace

TEST_CASE("mg_pcg from a start without z equals the start with z, bitwise", "[unit]") {
  core::Rng rng(18, 7);
  const int w = 37, h = 29;
  const Problem p = noisy_problem(w, h, rng);
  const size_t n = p.kernel.pixels();
  std::vector<Vec4> x0(n), g(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = to_vec4(p.primal[i]);
    g[i] = to_vec4(p.primal[i]);
  }
  for (const int threads : {1, 2}) {
    INFO("threads " << threads);
    GridOperator A(w, h);
    std::vector<Vec4d> rr(static_cast<size_t>(h)), bb(static_cast<size_t>(h));
    CgWorkspace with_z, without_z;
    with_z.r.resize(n);
    with_z.z.resize(n);
    without_z.r.resize(n);
    // Not read when first_red_done is false: NaN would show.
    without_z.z.assign(n, Vec4{1.0f, 1.0f, 1.0f, 1.0f} * std::numeric_limits<float>::quiet_NaN());
    A.reweight_start(x0.data(), p.b, g.data(), 1e-3, p.alpha, nullptr, nullptr, with_z.r.data(), with_z.z.data(),
                     rr.data(), bb.data(), threads);
    A.reweight_start(x0.data(), p.b, g.data(), 1e-3, p.alpha, nullptr, nullptr, without_z.r.data(), nullptr,
                     rr.data(), bb.data(), threads);
    GridMultigrid M;
    M.coarsest_pixels = 16;
    M.serial_pixels = 64;
    M.build(A, threads);
    CgSettings s;
    s.tolerance = 1e-6;
    s.threads = threads;
    s.max_iterations = 100;
    std::vector<Vec4> xa = x0, xb = x0;
    const CgStart a{rr.data(), bb.data(), true}, b{rr.data(), bb.data(), false};
    const CgStats sa = mg_pcg(A, M, nullptr, xa.data(), s, &with_z, &a);
    const CgStats sb = mg_pcg(A, M, nullptr, xb.data(), s, &without_z, &b);
    CHECK(sa.iterations >= 2);
    CHECK(sa.iterations == sb.iterations);
    CHECK(sa.relative_residual == sb.relative_residual);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(xa[i][c] == xb[i][c]);
  }
}

TEST_CASE("a converged start returns at once, without reading the hierarchy", "[unit]") {
  core::Rng rng(18, 8);
  const int w = 24, h = 20;
  const Problem p = noisy_problem(w, h, rng);
  const size_t n = p.kernel.pixels();
  std::vector<Vec4> x(n), g(n);
  for (size_t i = 0; i < n; ++i) x[i] = g[i] = to_vec4(p.primal[i]);
  GridOperator A(w, h);
  std::vector<Vec4d> rr(static_cast<size_t>(h)), bb(static_cast<size_t>(h));
  CgWorkspace ws;
  ws.r.resize(n);
  ws.z.resize(n);
  // IRLS at a fixed reg until a reweighting starts converged (its fixed point).
  GridMultigrid M;
  CgSettings tight;
  tight.tolerance = 1e-7;
  tight.max_iterations = 200;
  tight.threads = 1;
  CgSettings loose = tight;
  loose.tolerance = 1e-4;
  const CgStart start{rr.data(), bb.data(), false};
  bool converged = false;
  for (int k = 0; k < 100 && !converged; ++k) {
    A.reweight_start(x.data(), p.b, g.data(), 1e-2, p.alpha, nullptr, nullptr, ws.r.data(), nullptr, rr.data(),
                     bb.data(), 1);
    converged = cg_start_converged(start, h, loose.tolerance);
    if (k == 0) REQUIRE_FALSE(converged);
    if (converged) break;
    M.build(A, 1);
    REQUIRE(mg_pcg(A, M, nullptr, x.data(), tight, &ws, &start).converged);
  }
  REQUIRE(converged);
  GridMultigrid unbuilt;
  const std::vector<Vec4> before = x;
  const CgStats st = mg_pcg(A, unbuilt, nullptr, x.data(), loose, &ws, &start);
  CHECK(st.iterations == 0);
  CHECK(st.converged);
  CHECK(st.relative_residual <= loose.tolerance);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(x[i][c] == before[i][c]);
}

TEST_CASE("solve_l1 on the grid equals the earlier IRLS path bitwise", "[unit]") {
  core::Rng rng(18, 9);
  // 160x120: 3 multigrid levels with the library's defaults, some reweightings start
  // converged.
  const Problem p = noisy_problem(160, 120, rng);
  for (const int threads : {1, 2}) {
    INFO("threads " << threads);
    SolveOptions o;
    o.threads = threads;
    const SolveResult got = solve_l1(p, o);
    const Reference ref = reference_l1(p, threads);
    CHECK(got.cg_iterations == ref.cg_iterations);
    CHECK(got.relative_residual == ref.relative_residual);
    for (size_t i = 0; i < got.image.size(); ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(got.image[i][c] == ref.image[i][c]);
  }
}
