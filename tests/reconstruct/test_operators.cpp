// The CG operators (pcg.h): GridOperator vs the CSR Laplacian, the fused CG steps
// across chunk borders, the block incomplete Cholesky preconditioner, and the
// determinism of pcg() across thread counts.
#include <catch2/catch.hpp>

#include "helpers.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/pcg.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

std::vector<Vec4> precondition_all(const ChunkedOperator& A, const std::vector<Vec4>& r) {
  std::vector<Vec4> z(r.size());
  for (size_t c = 0; c < A.chunks(); ++c) A.precondition(c, r.data(), z.data());
  return z;
}

double dot(const std::vector<Vec4>& a, const std::vector<Vec4>& b, int c) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i][c]) * double(b[i][c]);
  return s;
}

double max_diff(const std::vector<Vec4>& a, const std::vector<Vec4>& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(double(a[i][c]) - double(b[i][c])));
  return m;
}

// Grid and CSR operators with the same random weights on a w x h grid (several chunks).
struct Pair {
  Kernel k;
  std::vector<float> rw, pw;
  GridOperator grid;
  Laplacian csr;
  Pair(int w, int h, core::Rng& rng, float alpha)
      : k(Kernel::forward_differences(w, h)), rw(k.rows()), pw(k.pixels()), grid(w, h), csr(k) {
    for (float& v : rw) v = 0.01f + 3.0f * rng.uniform();
    for (float& v : pw) v = 0.2f + rng.uniform();
    grid.set_weights(rw.data(), pw.data(), alpha, 2);
    csr.set_weights(rw.data(), pw.data(), alpha, 2);
  }
};

}  // namespace

TEST_CASE("GridOperator equals the CSR Laplacian of the grid kernel (A x, rhs, preconditioner)", "[unit]") {
  core::Rng rng(5, 4);
  Pair ops(37, 61, rng, 0.3f);
  REQUIRE(ops.grid.chunks() > 1);
  const std::vector<Vec4> x = random_vec4(ops.k.pixels(), rng);
  const std::vector<Vec4> a = apply_all(ops.grid, x), b = apply_all(ops.csr, x);
  CHECK(max_diff(a, b) < 1e-5);
  // ... and the 3-float CSR apply the dense tests check.
  std::vector<float> x3(3 * x.size()), y3(3 * x.size());
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t c = 0; c < 3; ++c) x3[3 * i + c] = x[i][int(c)];
  ops.csr.apply(x3.data(), y3.data(), 0, x.size());
  CHECK(max_diff(a, to_vec4(y3)) < 1e-5);

  std::vector<Rgb> bb(ops.k.rows());
  for (auto& v : bb) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  std::vector<Vec4> rg(x.size());
  ops.grid.rhs(bb, x.data(), rg.data(), 2);
  ops.csr.rhs(bb, x3.data(), y3.data(), 2);
  CHECK(max_diff(rg, to_vec4(y3)) < 1e-5);

  // Same entries in the same order: the two block factorizations agree.
  CHECK(max_diff(precondition_all(ops.grid, x), precondition_all(ops.csr, x)) < 1e-5);
}

TEST_CASE("the fused CG steps match their unfused definitions across chunk borders", "[unit]") {
  core::Rng rng(8, 1);
  Pair ops(23, 77, rng, 0.2f);
  Kernel adaptive = random_kernel(23, 77, 4, rng);
  Laplacian csr(adaptive);
  std::vector<float> rw(adaptive.rows());
  for (float& v : rw) v = 0.1f + rng.uniform();
  csr.set_weights(rw.data(), nullptr, 0.25f, 1);
  for (const ChunkedOperator* A : {static_cast<const ChunkedOperator*>(&ops.grid),
                                   static_cast<const ChunkedOperator*>(&ops.csr),
                                   static_cast<const ChunkedOperator*>(&csr)}) {
    const size_t n = A->pixels();
    REQUIRE(A->chunks() > 2);
    const std::vector<Vec4> z = random_vec4(n, rng), p_old = random_vec4(n, rng);
    const Vec4 beta = {0.3f, 0.7f, 1.1f, 0.0f};
    std::vector<Vec4> p_new(n), q(n), scratch(A->scratch_size());
    double pq[3] = {};
    for (size_t c = 0; c < A->chunks(); ++c) {
      Vec4d acc;
      A->direction(c, z.data(), p_old.data(), beta, p_new.data(), q.data(), acc, scratch.data());
      for (int ch = 0; ch < 3; ++ch) pq[ch] += acc[ch];
    }
    std::vector<Vec4> p_ref(n);
    for (size_t i = 0; i < n; ++i) p_ref[i] = z[i] + beta * p_old[i];
    CHECK(max_diff(p_new, p_ref) == 0.0);
    const std::vector<Vec4> q_ref = apply_all(*A, p_ref);
    CHECK(max_diff(q, q_ref) < 1e-5);
    for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(pq[ch] - dot(p_ref, q_ref, ch)) < 1e-6 * std::abs(pq[ch]) + 1e-9);

    // update(): x += alpha p, r -= alpha q, z = M^-1 r, r.z and r.r.
    std::vector<Vec4> x = random_vec4(n, rng), r = random_vec4(n, rng), zz(n);
    std::vector<Vec4> x_ref = x, r_ref = r;
    const Vec4 alpha = {0.5f, -0.25f, 2.0f, 0.0f};
    Vec4d rz, rr;
    for (size_t c = 0; c < A->chunks(); ++c) A->update(c, alpha, p_ref.data(), q.data(), x.data(), r.data(), zz.data(), rz, rr);
    for (size_t i = 0; i < n; ++i) {
      x_ref[i] += alpha * p_ref[i];
      r_ref[i] -= alpha * q[i];
    }
    CHECK(max_diff(x, x_ref) == 0.0);
    CHECK(max_diff(r, r_ref) == 0.0);
    const std::vector<Vec4> z_ref = precondition_all(*A, r_ref);
    CHECK(max_diff(zz, z_ref) == 0.0);
    for (int ch = 0; ch < 3; ++ch) {
      CHECK(std::abs(rz[ch] - dot(r_ref, z_ref, ch)) < 1e-6 * std::abs(rz[ch]));
      CHECK(std::abs(rr[ch] - dot(r_ref, r_ref, ch)) < 1e-6 * rr[ch]);
    }
  }
}

TEST_CASE("block incomplete Cholesky is symmetric positive definite, and exact on a chain", "[unit]") {
  core::Rng rng(13, 2);
  Pair ops(29, 50, rng, 0.2f);
  Kernel adaptive = random_kernel(29, 50, 3, rng);
  Laplacian csr(adaptive);
  std::vector<float> rw(adaptive.rows());
  for (float& v : rw) v = rng.uniform() < 0.1f ? 0.0f : 100.0f * rng.uniform();  // IRLS-like spread
  csr.set_weights(rw.data(), nullptr, 0.2f, 2);
  for (const ChunkedOperator* A : {static_cast<const ChunkedOperator*>(&ops.grid),
                                   static_cast<const ChunkedOperator*>(&csr)}) {
    for (int trial = 0; trial < 5; ++trial) {
      const std::vector<Vec4> u = random_vec4(A->pixels(), rng), v = random_vec4(A->pixels(), rng);
      const std::vector<Vec4> mu = precondition_all(*A, u), mv = precondition_all(*A, v);
      for (int c = 0; c < 3; ++c) {
        const double uv = dot(u, mv, c), vu = dot(mu, v, c);
        CHECK(std::abs(uv - vu) <= 1e-5 * (std::abs(uv) + std::abs(vu)) + 1e-9);
        CHECK(dot(u, mu, c) > 0.0);
      }
    }
  }
  // One image row = one chunk with a tridiagonal block: IC(0) has no fill to drop, so
  // the preconditioner is the exact inverse.
  GridOperator chain(200, 1);
  std::vector<float> cw(199);
  for (float& v : cw) v = 0.01f + 5.0f * rng.uniform();
  chain.set_weights(cw.data(), nullptr, 0.2f, 1);
  REQUIRE(chain.chunks() == 1);
  const std::vector<Vec4> r = random_vec4(200, rng);
  CHECK(max_diff(apply_all(chain, precondition_all(chain, r)), r) < 1e-5);
}

TEST_CASE("pcg gives bitwise identical results for 1 and 2 threads and with a reused workspace", "[unit]") {
  core::Rng rng(21, 3);
  Pair ops(24, 60, rng, 0.2f);
  Kernel adaptive = random_kernel(24, 60, 4, rng);
  Laplacian csr(adaptive);
  csr.set_weights(nullptr, nullptr, 0.2f, 2);
  const Eigen::MatrixXd dense[2] = {dense_matrix(ops.k, ops.rw, ops.pw, 0.2), dense_matrix(adaptive, {}, {}, 0.2)};
  for (int which = 0; which < 2; ++which) {
    const ChunkedOperator* A = which == 0 ? static_cast<const ChunkedOperator*>(&ops.grid) : &csr;
    REQUIRE(A->chunks() > 1);
    const std::vector<Vec4> rhs = random_vec4(A->pixels(), rng), x0 = random_vec4(A->pixels(), rng);
    CgSettings s;
    s.tolerance = 1e-6;
    std::vector<Vec4> x1 = x0, x2 = x0, x3 = x0;
    s.threads = 1;
    const CgStats a = pcg(*A, rhs.data(), x1.data(), s);
    s.threads = 2;
    const CgStats b = pcg(*A, rhs.data(), x2.data(), s);
    CgWorkspace ws;
    std::vector<Vec4> junk = x0;
    pcg(*A, x0.data(), junk.data(), s, &ws);  // leaves stale vectors in ws
    const CgStats c = pcg(*A, rhs.data(), x3.data(), s, &ws);
    INFO(a.iterations << " iterations, residual " << a.relative_residual);
    CHECK(a.converged);
    CHECK(a.relative_residual <= 1e-6);
    CHECK(a.iterations == b.iterations);
    CHECK(a.iterations == c.iterations);
    CHECK(max_diff(x1, x2) == 0.0);
    CHECK(max_diff(x1, x3) == 0.0);
    // The true residual of the stored x (in double) is as small as the recurrence says,
    // up to the float storage of x: rounding x moves A x by at most
    // |A|_2 |x| 2^-24 (|A|_2 <= max absolute row sum).
    const double norm_a = dense[which].cwiseAbs().rowwise().sum().maxCoeff();
    for (int ch = 0; ch < 3; ++ch) {
      Eigen::VectorXd xv(dense[which].rows()), bv(dense[which].rows());
      for (Eigen::Index i = 0; i < xv.size(); ++i) {
        xv(i) = double(x1[size_t(i)][ch]);
        bv(i) = double(rhs[size_t(i)][ch]);
      }
      const double floor = norm_a * xv.norm() * std::ldexp(1.0, -24) / bv.norm();
      INFO("operator " << which << " channel " << ch << ", float floor " << floor);
      CHECK((dense[which] * xv - bv).norm() / bv.norm() <= 2e-6 + 2.0 * floor);
    }
  }
}

TEST_CASE("GridOperator IRLS reweighting equals the weights computed over the kernel's pairs", "[unit]") {
  core::Rng rng(17, 5);
  const int w = 31, h = 53;
  const Kernel k = Kernel::forward_differences(w, h);
  const std::vector<Vec4> x = random_vec4(k.pixels(), rng), g = random_vec4(k.pixels(), rng);
  std::vector<Rgb> b(k.rows());
  for (auto& v : b) v = Rgb(rng.uniform() - 0.5f, rng.uniform(), -rng.uniform());
  std::vector<float> user_rows(k.rows()), user_pixels(k.pixels());
  for (float& v : user_rows) v = 0.5f + rng.uniform();
  for (float& v : user_pixels) v = 0.5f + rng.uniform();
  const double reg = 0.05 * std::pow(0.5, 3), alpha = double(0.2f);
  // Reference: ALGORITHMS.md's IRLS weights over every pair and pixel, in double.
  std::vector<double> rw(k.rows()), pw(k.pixels());
  double total = 0.0;
  for (size_t r = 0; r < k.rows(); ++r) {
    const auto [i, j] = k.pairs()[r];
    double e2 = 0.0;
    for (int c = 0; c < 3; ++c) e2 += std::pow(double(x[size_t(j)][c]) - double(x[size_t(i)][c]) - double(b[r][c]), 2);
    rw[r] = 1.0 / (std::sqrt(e2) + reg);
    total += rw[r];
  }
  for (size_t i = 0; i < k.pixels(); ++i) {
    double e2 = 0.0;
    for (int c = 0; c < 3; ++c) e2 += std::pow(alpha * (double(x[i][c]) - double(g[i][c])), 2);
    pw[i] = 1.0 / (std::sqrt(e2) + reg);
    total += pw[i];
  }
  const double scale = double(k.rows() + k.pixels()) / total;
  std::vector<float> rwf(k.rows()), pwf(k.pixels());
  for (size_t r = 0; r < k.rows(); ++r) rwf[r] = float(rw[r] * scale * double(user_rows[r]));
  for (size_t i = 0; i < k.pixels(); ++i) pwf[i] = float(pw[i] * scale * double(user_pixels[i]));
  Laplacian ref(k);
  ref.set_weights(rwf.data(), pwf.data(), float(alpha), 1);
  GridOperator grid(w, h);
  const double raw_total = grid.set_irls_weights(x.data(), b, g.data(), reg, float(alpha), user_rows.data(),
                                                 user_pixels.data(), 2);
  CHECK(std::abs(raw_total - total) < 1e-12 * total);
  const std::vector<Vec4> v = random_vec4(k.pixels(), rng);
  const std::vector<Vec4> a = apply_all(grid, v), e = apply_all(ref, v);
  double scale_a = 0.0;
  for (const Vec4& q : e) scale_a = std::max(scale_a, double(std::abs(q[0]) + std::abs(q[1]) + std::abs(q[2])));
  CHECK(max_diff(a, e) < 1e-5 * scale_a);
  CHECK(max_diff(precondition_all(grid, v), precondition_all(ref, v)) < 1e-5 * scale_a);
}
