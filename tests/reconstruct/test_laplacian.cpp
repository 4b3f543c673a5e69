// The normal-equation operator H^T W H + alpha^2 P (reconstruct/laplacian.h).
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "helpers.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

TEST_CASE("H^T W H of random kernels is symmetric PSD with zero row sums", "[unit]") {
  for (uint64_t seed = 0; seed < 6; ++seed) {
    core::Rng rng(seed, 1);
    const int w = 7 + int(seed), h = 5 + int(seed % 3);
    const Kernel k = random_kernel(w, h, 1 + int(seed % 4), rng);
    std::vector<float> rw(k.rows());
    for (float& v : rw) v = (seed % 2) ? 0.05f + 2.0f * rng.uniform() : 1.0f;
    Laplacian L(k);
    L.set_weights(rw.data(), nullptr, 0.0f, 1);
    const Eigen::MatrixXd M = operator_matrix(L);
    INFO("seed " << seed);
    // Same matrix as the independent dense assembly (float weights: 1e-6 relative).
    CHECK((M - dense_matrix(k, rw, {}, 0.0)).cwiseAbs().maxCoeff() < 1e-5 * M.cwiseAbs().maxCoeff());
    CHECK((M - M.transpose()).cwiseAbs().maxCoeff() == 0.0);
    // Row sums vanish up to the float rounding of the stored diagonal (deg * 2^-24 relative).
    const double row_sum = M.rowwise().sum().cwiseAbs().maxCoeff();
    CHECK(row_sum <= 1e-6 * M.diagonal().maxCoeff());
    // M = M0 + E with M0 exactly PSD with zero row sums and E = diag(row sums):
    // Weyl gives |lambda_min(M)| <= |E| (plus the eigensolver's own 1e-12 relative error).
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    const double slack = row_sum + 1e-12 * ev.maxCoeff();
    CHECK(ev.minCoeff() >= -slack);
    // The constant vector spans (part of) the null space: lambda_min = 0.
    CHECK(std::abs(ev.minCoeff()) <= slack);
  }
}

TEST_CASE("with alpha > 0 the system is SPD with lambda_min >= alpha^2 min p", "[unit]") {
  core::Rng rng(7, 2);
  const Kernel k = random_kernel(9, 6, 3, rng);
  std::vector<float> pw(k.pixels());
  for (float& v : pw) v = 0.5f + rng.uniform();
  const float alpha = 0.2f;
  Laplacian L(k);
  L.set_weights(nullptr, pw.data(), alpha, 2);
  const Eigen::MatrixXd M = operator_matrix(L);
  CHECK((M - M.transpose()).cwiseAbs().maxCoeff() == 0.0);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
  const double pmin = double(*std::min_element(pw.begin(), pw.end()));
  // Weyl: lambda_min(L + alpha^2 P) >= lambda_min(L) + alpha^2 min p = alpha^2 min p.
  CHECK(ev.minCoeff() >= 0.04 * pmin * (1.0 - 1e-5));
  CHECK(Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success);
}

TEST_CASE("grid Laplacian is the 5-point stencil with Neumann boundaries", "[unit]") {
  const int w = 6, h = 4;
  const Kernel k = Kernel::forward_differences(w, h);
  CHECK(k.rows() == size_t((w - 1) * h + w * (h - 1)));
  CHECK(k.is_forward_difference_grid());
  Laplacian L(k);
  L.set_weights(nullptr, nullptr, 0.0f, 1);
  const Eigen::MatrixXd M = operator_matrix(L);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = y * w + x;
      int nbrs = 0;
      for (int yy = 0; yy < h; ++yy)
        for (int xx = 0; xx < w; ++xx) {
          const int j = yy * w + xx;
          if (j == i) continue;
          const bool adjacent = std::abs(xx - x) + std::abs(yy - y) == 1;
          nbrs += adjacent;
          INFO("pixel (" << x << "," << y << ") vs (" << xx << "," << yy << ")");
          CHECK(M(i, j) == (adjacent ? -1.0 : 0.0));
        }
      // Neumann: the diagonal counts only in-image neighbours (4 inside, 3 on edges, 2 in corners).
      CHECK(M(i, i) == double(nbrs));
      CHECK(nbrs == 4 - (x == 0) - (x == w - 1) - (y == 0) - (y == h - 1));
    }
}

TEST_CASE("Laplacian right-hand side equals H^T W b + alpha^2 P g", "[unit]") {
  core::Rng rng(3, 3);
  const Kernel k = random_kernel(8, 7, 2, rng);
  std::vector<Rgb> b(k.rows());
  for (auto& v : b) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  std::vector<float> rw(k.rows()), pw(k.pixels()), g(3 * k.pixels());
  for (float& v : rw) v = rng.uniform();
  for (float& v : pw) v = 0.5f + rng.uniform();
  for (float& v : g) v = rng.uniform();
  Laplacian L(k);
  L.set_weights(rw.data(), pw.data(), 0.3f, 2);
  std::vector<float> out(g.size());
  L.rhs(b, g.data(), out.data(), 2);
  std::vector<double> ref(g.size(), 0.0);
  for (size_t i = 0; i < k.pixels(); ++i)
    for (size_t c = 0; c < 3; ++c) ref[3 * i + c] = 0.09 * double(pw[i]) * double(g[3 * i + c]);
  for (size_t r = 0; r < k.rows(); ++r)
    for (size_t c = 0; c < 3; ++c) {
      ref[3 * size_t(k.pairs()[r].j) + c] += double(rw[r]) * double(b[r][int(c)]);
      ref[3 * size_t(k.pairs()[r].i) + c] -= double(rw[r]) * double(b[r][int(c)]);
    }
  for (size_t i = 0; i < g.size(); ++i) CHECK(std::abs(double(out[i]) - ref[i]) < 1e-5);
}
