// mg_pcg (mg_pcg.cpp, issue 18) with its fused passes (the V-cycle's first red
// half-step inside the CG update, p formed inside q = A p) and a run ending after any
// number of iterations, against a textbook PCG that applies the same V-cycle
// (GridMultigrid::apply) and the operator one step at a time.
#include <catch2/catch.hpp>

#include "helpers.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/multigrid.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

Vec4d dot(const std::vector<Vec4>& a, const std::vector<Vec4>& b) {
  Vec4d s;
  for (size_t i = 0; i < a.size(); ++i) accumulate(s, a[i] * b[i]);
  return s;
}

// `iterations` steps of PCG with M^-1 = one V-cycle, three channels side by side.
std::vector<Vec4> textbook_pcg(const GridOperator& A, GridMultigrid& M, const std::vector<Vec4>& rhs,
                               std::vector<Vec4> x, int iterations) {
  const size_t n = x.size();
  std::vector<Vec4> r(n), z(n), p(n);
  const std::vector<Vec4> ax = apply_all(A, x);
  for (size_t i = 0; i < n; ++i) r[i] = rhs[i] - ax[i];
  M.apply(r.data(), z.data());
  p = z;
  Vec4d rz = dot(r, z);
  for (int it = 0; it < iterations; ++it) {
    const std::vector<Vec4> q = apply_all(A, p);
    const Vec4d pq = dot(p, q);
    Vec4 alpha = {};
    for (int c = 0; c < 3; ++c) alpha[c] = float(rz[c] / pq[c]);
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    M.apply(r.data(), z.data());
    const Vec4d rz_new = dot(r, z);
    Vec4 beta = {};
    for (int c = 0; c < 3; ++c) beta[c] = float(rz_new[c] / rz[c]);
    rz = rz_new;
    for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  return x;
}

}  // namespace

TEST_CASE("mg_pcg follows textbook PCG with the same V-cycle, iteration by iteration", "[unit]") {
  core::Rng rng(18, 7);
  const int w = 37, h = 29;
  const Kernel k = Kernel::forward_differences(w, h);
  std::vector<float> rw(k.rows()), pw(k.pixels());
  for (float& v : rw) v = float(std::pow(10.0, 2.0 * (double(rng.uniform()) - 0.5)));
  for (float& v : pw) v = 0.5f + rng.uniform();
  GridOperator A(w, h);
  A.set_weights(rw.data(), pw.data(), 0.2f, 1);
  GridMultigrid M;
  M.coarsest_pixels = 16;
  M.serial_pixels = 64;  // level 1 split between the threads too
  M.build(A, 2);
  REQUIRE(M.levels().size() >= 3);
  const std::vector<Vec4> rhs = random_vec4(k.pixels(), rng), x0 = random_vec4(k.pixels(), rng);
  for (int iterations = 1; iterations <= 5; ++iterations)
    for (const int threads : {1, 2}) {
      INFO(iterations << " iterations, " << threads << " threads");
      const std::vector<Vec4> expect = textbook_pcg(A, M, rhs, x0, iterations);
      std::vector<Vec4> x = x0;
      CgSettings s;
      s.max_iterations = iterations;
      s.tolerance = 1e-12;  // never reached: exactly `iterations` steps
      s.threads = threads;
      CgWorkspace ws;
      const CgStats st = mg_pcg(A, M, rhs.data(), x.data(), s, &ws);
      CHECK(st.iterations == iterations);
      double err = 0.0, step = 0.0;
      for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          err = std::max(err, std::abs(double(x[i][c]) - double(expect[i][c])));
          step = std::max(step, std::abs(double(expect[i][c]) - double(x0[i][c])));
        }
      INFO("max difference " << err << " (largest change of x " << step << ")");
      CHECK(err < 1e-4 * step);
    }
}
