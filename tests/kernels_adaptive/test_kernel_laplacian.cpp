// The Laplacian H^T H + alpha^2 I of an adaptive kernel (Manzi et al. 2014, Eq. 9) is
// symmetric positive definite, reconstruct/ builds the same operator, and H^T H alone
// vanishes exactly on the functions constant on each connected part of the N_i graph.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "helpers.h"
#include "reconstruct/laplacian.h"

using namespace dp;
using namespace dp::kernels_adaptive;

namespace {

Eigen::MatrixXd dense_normal_matrix(const PairKernel& k, double alpha) {
  const int n = k.width * k.height;
  Eigen::MatrixXd A = alpha * alpha * Eigen::MatrixXd::Identity(n, n);
  for (const auto& row : k.rows) {  // row: (H I)_r = I[b] - I[a]
    A(row.i, row.i) += 1.0;
    A(row.j, row.j) += 1.0;
    A(row.i, row.j) -= 1.0;
    A(row.j, row.i) -= 1.0;
  }
  return A;
}

// Connected components of the graph i -- j for j in N_i: a label per pixel.
std::vector<int> components(const PairKernel& k) {
  const int n = k.width * k.height;
  std::vector<int> label(size_t(n), -1);
  int count = 0;
  for (int s = 0; s < n; ++s) {
    if (label[size_t(s)] >= 0) continue;
    std::vector<int> stack{s};
    label[size_t(s)] = count;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (const auto& e : neighbours(k, i))
        if (label[size_t(e.j)] < 0) {
          label[size_t(e.j)] = count;
          stack.push_back(e.j);
        }
    }
    ++count;
  }
  return label;
}

}  // namespace

TEST_CASE("adaptive kernel Laplacian H^T H + alpha^2 I is SPD and matches reconstruct/", "[unit]") {
  for (uint64_t seed = 0; seed < 3; ++seed) {
    core::Rng rng(seed, 9);
    const int w = 11, h = 8;
    Features f = test::synthetic_features(w, h, 3, rng);
    if (seed == 2)  // an isolated 2x2 island of very different albedo: its own component
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) f.albedo[size_t(y * w + x)] = Rgb(1.0f, 1.0f, 1.0f);
    AffinityParams p;
    if (seed == 2) p.neighbours = 3;
    const PairKernel k = adaptive_kernel(f, p);
    INFO("seed " << seed);
    const double alpha = 0.2;
    const Eigen::MatrixXd A = dense_normal_matrix(k, alpha);
    CHECK((A - A.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(Eigen::LLT<Eigen::MatrixXd>(A).info() == Eigen::Success);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
    CHECK(ev.minCoeff() >= alpha * alpha * (1.0 - 1e-9));
    // Rayleigh quotients of random vectors: x^T A x = |H x|^2 + alpha^2 |x|^2 > 0.
    for (int t = 0; t < 5; ++t) {
      Eigen::VectorXd x(w * h);
      for (int i = 0; i < w * h; ++i) x(i) = double(rng.uniform()) - 0.5;
      double hx2 = 0.0;
      for (const auto& row : k.rows) hx2 += (x(row.j) - x(row.i)) * (x(row.j) - x(row.i));
      CHECK(x.dot(A * x) == Approx(hx2 + alpha * alpha * x.squaredNorm()).epsilon(1e-12));
      CHECK(x.dot(A * x) > 0.0);
    }
    // H^T H: null space = constants on each component of the N_i graph (rows and N_i
    // describe the same graph).
    const Eigen::VectorXd ev0 =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense_normal_matrix(k, 0.0)).eigenvalues();
    int zero = 0;
    for (int i = 0; i < ev0.size(); ++i) zero += std::abs(ev0(i)) < 1e-9;
    const std::vector<int> label = components(k);
    CHECK(zero == *std::max_element(label.begin(), label.end()) + 1);
    if (seed == 2) {  // the island is one component of its own
      const int island = label[0];
      for (int i = 0; i < w * h; ++i) CHECK((label[size_t(i)] == island) == (i % w < 2 && i / w < 2));
    }
    // reconstruct::Laplacian on the same rows is the same matrix.
    const reconstruct::Kernel rk(w, h, k.rows);
    reconstruct::Laplacian L(rk);
    L.set_weights(nullptr, nullptr, float(alpha), 1);
    std::vector<float> in(size_t(3 * w * h), 0.0f), out(in.size());
    for (int c = 0; c < w * h; ++c) {
      in[size_t(3 * c)] = 1.0f;
      L.apply(in.data(), out.data(), 0, size_t(w * h));
      for (int r = 0; r < w * h; ++r) CHECK(std::abs(double(out[size_t(3 * r)]) - A(r, c)) < 1e-6);
      in[size_t(3 * c)] = 0.0f;
    }
  }
}
