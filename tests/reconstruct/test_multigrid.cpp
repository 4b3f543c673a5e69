// Multigrid-preconditioned CG on the grid operator (multigrid.h, issue 18): the Galerkin
// hierarchy, the symmetry and definiteness of the V-cycle, agreement with the dense /
// DCT / block-IC solves for L2 and L1, and determinism across thread counts.
#include <catch2/catch.hpp>

#include "helpers.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/multigrid.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

// Random positive weights spanning `spread` orders of magnitude (IRLS weights do).
std::vector<float> random_weights(size_t n, core::Rng& rng, double spread) {
  std::vector<float> w(n);
  for (float& v : w) v = float(std::pow(10.0, spread * (double(rng.uniform()) - 0.5)));
  return w;
}

// Dense matrix of the grid operator (channel 0), by applying it to unit vectors.
Eigen::MatrixXd dense_grid(const Kernel& k, const std::vector<float>& rw, const std::vector<float>& pw, double alpha) {
  return dense_matrix(k, rw, pw, alpha);
}

// Dense matrix of the level-l operator of the hierarchy from its per-pixel arrays.
Eigen::MatrixXd dense_level(const GridMultigrid::Level& L) {
  const Eigen::Index n = Eigen::Index(L.w) * L.h;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int y = 0; y < L.h; ++y)
    for (int x = 0; x < L.w; ++x) {
      const Eigen::Index i = Eigen::Index(y) * L.w + x;
      A(i, i) = L.diag[i];
      if (x + 1 < L.w) A(i, i + 1) = A(i + 1, i) = -double(L.wx[i]);
      if (y + 1 < L.h) A(i, i + L.w) = A(i + L.w, i) = -double(L.wy[i]);
    }
  return A;
}

// Piecewise-constant prolongation from level (W, H) to (w, h): fine (x, y) <- (x/2, y/2).
Eigen::MatrixXd prolongation(int w, int h, int W, int H) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(Eigen::Index(w) * h, Eigen::Index(W) * H);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) P(Eigen::Index(y) * w + x, Eigen::Index(y / 2) * W + x / 2) = 1.0;
  return P;
}

// The V-cycle M^-1 as a dense matrix (channel 0; channels 1, 2 get other unit vectors
// scaled, to check the channels do not mix).
Eigen::MatrixXd dense_vcycle(GridMultigrid& M, size_t n) {
  const auto dim = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd out(dim, dim);
  std::vector<Vec4> r(n, Vec4{}), z(n);
  for (size_t k = 0; k < n; ++k) {
    r[k] = Vec4{1.0f, 0.0f, 0.0f, 0.0f};
    M.apply(r.data(), z.data());
    for (size_t i = 0; i < n; ++i) {
      out(Eigen::Index(i), Eigen::Index(k)) = double(z[i][0]);
      REQUIRE(z[i][1] == 0.0f);
    }
    r[k] = Vec4{};
  }
  return out;
}

Problem random_grid_problem(int w, int h, core::Rng& rng, float alpha) {
  Problem p;
  p.kernel = Kernel::forward_differences(w, h);
  p.primal = test_image(w, h);
  for (auto& v : p.primal.pixels())
    for (int c = 0; c < 3; ++c) v[c] += float(0.2 * gaussian(rng));
  p.b = apply_kernel(p.kernel, test_image(w, h));
  // Random gradient field on top of the image's own (with a few outliers for L1).
  for (size_t r = 0; r < p.b.size(); ++r) {
    for (int c = 0; c < 3; ++c) p.b[r][c] += float(0.05 * gaussian(rng));
    if (r % 97 == 0) p.b[r] += Rgb(2.0f, -1.5f, 3.0f);
  }
  p.alpha = alpha;
  return p;
}

double rms_diff(const core::Image& a, const core::Image& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += double((a[i] - b[i]).matrix().squaredNorm());
  return std::sqrt(s / double(3 * a.size()));
}

SolveOptions grid_options(GridSolver solver, L2Method method, int threads = 2) {
  SolveOptions o;
  o.grid_solver = solver;
  o.method = method;
  o.threads = threads;
  return o;
}

}  // namespace

TEST_CASE("multigrid levels are the Galerkin operators P^T A P of 2x2 aggregation", "[unit]") {
  core::Rng rng(31, 0);
  for (const auto& [w, h] : {std::pair{11, 9}, std::pair{8, 6}, std::pair{7, 1}}) {
    INFO(w << "x" << h);
    const Kernel k = Kernel::forward_differences(w, h);
    const std::vector<float> rw = random_weights(k.rows(), rng, 3.0), pw = random_weights(k.pixels(), rng, 2.0);
    GridOperator A(w, h);
    A.set_weights(rw.data(), pw.data(), 0.3f, 1);
    GridMultigrid M;
    M.coarsest_pixels = 1;
    M.build(A, 1);
    REQUIRE(M.levels().size() >= 3);
    Eigen::MatrixXd fine = dense_grid(k, rw, pw, 0.3);
    CHECK((dense_level(M.levels()[0]) - fine).cwiseAbs().maxCoeff() < 1e-5 * fine.cwiseAbs().maxCoeff());
    for (size_t l = 1; l < M.levels().size(); ++l) {
      const auto& f = M.levels()[l - 1];
      const auto& c = M.levels()[l];
      CHECK(c.w == (f.w + 1) / 2);
      CHECK(c.h == (f.h + 1) / 2);
      const Eigen::MatrixXd P = prolongation(f.w, f.h, c.w, c.h);
      const Eigen::MatrixXd galerkin = P.transpose() * fine * P;
      const Eigen::MatrixXd coarse = dense_level(c);
      CHECK((coarse - galerkin).cwiseAbs().maxCoeff() < 1e-5 * galerkin.cwiseAbs().maxCoeff());
      fine = galerkin;
    }
  }
}

TEST_CASE("the multigrid V-cycle is a symmetric positive definite preconditioner", "[unit]") {
  core::Rng rng(32, 0);
  const int w = 13, h = 10;
  const Kernel k = Kernel::forward_differences(w, h);
  const std::vector<float> rw = random_weights(k.rows(), rng, 4.0), pw = random_weights(k.pixels(), rng, 2.0);
  GridOperator A(w, h);
  A.set_weights(rw.data(), pw.data(), 0.2f, 1);
  for (const int sweeps : {1, 2}) {
    GridMultigrid M;
    M.coarsest_pixels = 4;
    M.pre_sweeps = sweeps;
    M.build(A, 1);
    REQUIRE(M.levels().size() >= 3);
    const Eigen::MatrixXd Minv = dense_vcycle(M, k.pixels());
    const double scale = Minv.cwiseAbs().maxCoeff();
    CHECK((Minv - Minv.transpose()).cwiseAbs().maxCoeff() < 1e-5 * scale);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (Minv + Minv.transpose())).eigenvalues();
    CHECK(ev.minCoeff() > 0.0);
    // A good preconditioner: the spectrum of M^-1 A is clustered (condition number of A
    // itself is ~1e5 here).
    const Eigen::MatrixXd Ad = dense_grid(k, rw, pw, 0.2);
    const Eigen::VectorXcd lam = (Minv * Ad).eigenvalues();
    double lo = 1e300, hi = 0.0;
    for (Eigen::Index i = 0; i < lam.size(); ++i) {
      lo = std::min(lo, lam[i].real());
      hi = std::max(hi, lam[i].real());
    }
    INFO("sweeps " << sweeps << ": eigenvalues of M^-1 A in [" << lo << ", " << hi << "]");
    CHECK(lo > 0.0);
    CHECK(hi <= 1.0 + 1e-4);  // a symmetric V-cycle with Galerkin coarsening never over-corrects
    CHECK(hi / lo < (sweeps == 1 ? 50.0 : 20.0));
  }
}

TEST_CASE("multigrid PCG matches a dense solve on weighted grids, in few iterations", "[unit]") {
  core::Rng rng(33, 0);
  const int w = 23, h = 17;
  const Kernel k = Kernel::forward_differences(w, h);
  for (const double spread : {0.0, 2.0, 5.0}) {
    INFO("weight spread 1e" << spread);
    Problem p = random_grid_problem(w, h, rng, 0.25f);
    p.row_weights = random_weights(k.rows(), rng, spread);
    p.pixel_weights = random_weights(k.pixels(), rng, spread / 2.0);
    const core::Image exact = dense_solve(p);
    GridOperator A(w, h);
    A.set_weights(p.row_weights.data(), p.pixel_weights.data(), p.alpha, 1);
    std::vector<Vec4> g(k.pixels()), rhs(k.pixels()), x(k.pixels());
    for (size_t i = 0; i < g.size(); ++i) g[i] = to_vec4(p.primal[i]);
    A.rhs(p.b, g.data(), rhs.data(), 1);
    for (const int threads : {1, 2}) {
      GridMultigrid M;
      M.coarsest_pixels = 8;
      M.serial_pixels = 16;  // parallel coarse levels too
      M.build(A, threads);
      x = g;
      CgSettings s;
      s.tolerance = 1e-6;
      s.max_iterations = 100;
      s.threads = threads;
      const CgStats st = mg_pcg(A, M, rhs.data(), x.data(), s);
      CHECK(st.converged);
      CHECK(st.relative_residual <= 1e-6);
      CHECK(st.iterations <= (spread > 3.0 ? 60 : 15));
      double err = 0.0, mag = 0.0;
      for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          err = std::max(err, std::abs(double(x[i][c]) - double(exact[i][c])));
          mag = std::max(mag, std::abs(double(exact[i][c])));
        }
      INFO("threads " << threads << ", iterations " << st.iterations << ", max error " << err);
      CHECK(err < 2e-5 * std::max(1.0, mag) * (spread > 3.0 ? 10.0 : 1.0));
    }
  }
}

TEST_CASE("multigrid PCG gives bitwise identical results for 1 and 2 threads", "[unit]") {
  core::Rng rng(34, 0);
  const int w = 97, h = 75;
  const Kernel k = Kernel::forward_differences(w, h);
  const Problem p = random_grid_problem(w, h, rng, 0.2f);
  const std::vector<float> rw = random_weights(k.rows(), rng, 3.0);
  GridOperator A(w, h);
  A.set_weights(rw.data(), nullptr, p.alpha, 2);
  std::vector<Vec4> g(k.pixels()), rhs(k.pixels());
  for (size_t i = 0; i < g.size(); ++i) g[i] = to_vec4(p.primal[i]);
  A.rhs(p.b, g.data(), rhs.data(), 2);
  std::vector<std::vector<Vec4>> out;
  std::vector<int> its;
  for (const int threads : {1, 2, 2}) {
    GridMultigrid M;
    M.coarsest_pixels = 30;
    M.serial_pixels = 200;  // levels 0-3 run split between the threads
    M.build(A, threads);
    std::vector<Vec4> x = g;
    CgSettings s;
    s.tolerance = 1e-6;
    s.threads = threads;
    CgWorkspace ws;
    its.push_back(mg_pcg(A, M, rhs.data(), x.data(), s, &ws).iterations);
    out.push_back(x);
  }
  CHECK(its[0] == its[1]);
  CHECK(its[1] == its[2]);
  for (size_t i = 0; i < g.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      REQUIRE(out[0][i][c] == out[1][i][c]);
      REQUIRE(out[1][i][c] == out[2][i][c]);
    }
}

TEST_CASE("solve_l2 / solve_l1 with the multigrid grid solver match DCT and block-IC solves", "[unit]") {
  core::Rng rng(35, 0);
  // 160x120: 3 multigrid levels with the library's defaults.
  const int w = 160, h = 120;
  const Problem p = random_grid_problem(w, h, rng, 0.2f);
  // L2, uniform weights: CG to 1e-6 against the exact DCT solve.
  const SolveResult dct = solve_l2(p, grid_options(GridSolver::multigrid, L2Method::direct));
  const SolveResult mg = solve_l2(p, grid_options(GridSolver::multigrid, L2Method::cg));
  CHECK(mg.preconditioner == "multigrid");
  CHECK(mg.relative_residual <= 1e-6);
  CHECK(max_abs_diff(mg.image, dct.image) < 1e-5);
  const SolveResult ic = solve_l2(p, grid_options(GridSolver::block_ic, L2Method::cg));
  CHECK(ic.preconditioner == "block_ic");
  INFO("L2 CG iterations: multigrid " << mg.cg_iterations << ", block IC " << ic.cg_iterations);
  CHECK(mg.cg_iterations * 2 < ic.cg_iterations);

  // L2 with row and pixel weights (CG path only).
  Problem pw = p;
  pw.row_weights = random_weights(p.kernel.rows(), rng, 2.0);
  pw.pixel_weights = random_weights(p.kernel.pixels(), rng, 1.0);
  const SolveResult mgw = solve_l2(pw, grid_options(GridSolver::multigrid, L2Method::automatic));
  const SolveResult icw = solve_l2(pw, grid_options(GridSolver::block_ic, L2Method::automatic));
  CHECK(max_abs_diff(mgw.image, icw.image) < 2e-4);

  // L1 (IRLS, inner CG to relative residual 1e-4): the two inner solvers agree within
  // what that tolerance allows, and both are as close to a tightly solved IRLS.
  SolveOptions tight = grid_options(GridSolver::block_ic, L2Method::automatic);
  tight.irls_cg_tolerance = 1e-7;
  tight.irls_cg_iterations = 1000;
  const SolveResult ref = solve_l1(p, tight);
  const SolveResult l1_mg = solve_l1(p, grid_options(GridSolver::multigrid, L2Method::automatic));
  const SolveResult l1_ic = solve_l1(p, grid_options(GridSolver::block_ic, L2Method::automatic));
  CHECK(l1_mg.preconditioner == "multigrid");
  CHECK(l1_mg.reweightings == 20);
  const double d_mg = max_abs_diff(l1_mg.image, ref.image), d_ic = max_abs_diff(l1_ic.image, ref.image);
  const double o_ref = l1_objective(p, ref.image), o_mg = l1_objective(p, l1_mg.image),
               o_ic = l1_objective(p, l1_ic.image);
  INFO("L1 objective: tight " << o_ref << ", multigrid " << o_mg << ", block IC " << o_ic);
  INFO("L1: multigrid vs tight " << d_mg << ", block IC vs tight " << d_ic << ", multigrid vs block IC "
                                 << max_abs_diff(l1_mg.image, l1_ic.image) << "; CG iterations " << l1_mg.cg_iterations
                                 << " vs " << l1_ic.cg_iterations);
  // IRLS with an inner tolerance of 1e-4 is itself ~1e-1 (max) away from the tightly
  // solved IRLS near the outliers; the multigrid inner solver must be as close as the
  // block-IC one, in the image and in the L1 objective.
  const double r_mg = rms_diff(l1_mg.image, ref.image), r_ic = rms_diff(l1_ic.image, ref.image);
  INFO("L1 rms vs tight: multigrid " << r_mg << ", block IC " << r_ic);
  CHECK(r_mg <= 1.5 * r_ic + 1e-5);
  CHECK(d_mg <= 1.5 * d_ic + 1e-4);
  CHECK(o_mg - o_ref <= 1.5 * (o_ic - o_ref) + 1e-6 * o_ref);
  CHECK(rms_diff(l1_mg.image, l1_ic.image) < 1e-2);
  CHECK(l1_mg.cg_iterations < l1_ic.cg_iterations);
}
