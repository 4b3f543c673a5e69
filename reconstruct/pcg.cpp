#include "reconstruct/pcg.h"

#include <algorithm>
#include <barrier>
#include <cmath>

#include "core/error.h"

namespace dp::reconstruct {

namespace {

// Per-thread partial sums, one cache line apart. Slots: [0..3) r.z, [3..6) r.r,
// [6..9) rhs.rhs or p.Ap.
struct alignas(64) Partial {
  double v[9] = {};
};

void reduce(const std::vector<Partial>& parts, double out[9]) {
  std::fill(out, out + 9, 0.0);
  for (const Partial& p : parts)  // fixed order: deterministic
    for (int k = 0; k < 9; ++k) out[k] += p.v[k];
}

}  // namespace

CgStats pcg(const Laplacian& A, const float* rhs, float* x, const CgSettings& settings) {
  const size_t n = A.pixels();
  DP_CHECK(settings.max_iterations >= 0, "max_iterations must be >= 0");
  const int threads = int(std::max<size_t>(1, std::min<size_t>(size_t(resolve_threads(settings.threads)), n / 4096 + 1)));
  std::vector<float> r(3 * n), p(3 * n), q(3 * n);
  std::vector<Partial> part_a(static_cast<size_t>(threads)), part_b(static_cast<size_t>(threads));
  std::barrier sync(threads);
  const float* inv_diag = A.inv_diag();
  CgStats stats;

  run_team(threads, [&](int t) {
    const size_t lo = part_begin(n, threads, t), hi = part_begin(n, threads, t + 1);
    double tot[9];
    // r = rhs - A x, p = M^-1 r.
    A.apply(x, q.data(), lo, hi);
    {
      Partial acc;
      for (size_t i = lo; i < hi; ++i) {
        const float m = inv_diag[i];
        for (size_t c = 0; c < 3; ++c) {
          const size_t k = 3 * i + c;
          const float ri = rhs[k] - q[k];
          r[k] = ri;
          p[k] = m * ri;
          acc.v[c] += double(ri) * double(m * ri);
          acc.v[3 + c] += double(ri) * double(ri);
          acc.v[6 + c] += double(rhs[k]) * double(rhs[k]);
        }
      }
      part_b[size_t(t)] = acc;
    }
    sync.arrive_and_wait();
    reduce(part_b, tot);
    double rz[3], limit[3], rr[3];
    bool active[3];
    for (int c = 0; c < 3; ++c) {
      rz[c] = tot[c];
      rr[c] = tot[3 + c];
      // An all-zero right-hand side has the solution 0: stop at a tiny absolute residual.
      limit[c] = settings.tolerance * std::sqrt(std::max(tot[6 + c], 1e-60));
      active[c] = std::sqrt(rr[c]) > limit[c];
    }
    const double bnorm2[3] = {tot[6], tot[7], tot[8]};
    int it = 0;
    while (it < settings.max_iterations && (active[0] || active[1] || active[2])) {
      // q = A p, alpha = (r.z) / (p.q).
      {
        Partial acc;
        A.apply_dot(p.data(), q.data(), lo, hi, acc.v + 6);
        part_a[size_t(t)] = acc;
      }
      sync.arrive_and_wait();
      reduce(part_a, tot);
      float step[3];
      for (int c = 0; c < 3; ++c)
        step[c] = active[c] && tot[6 + c] > 0.0 ? float(rz[c] / tot[6 + c]) : 0.0f;
      // x += alpha p, r -= alpha q, new r.z and r.r.
      {
        Partial acc;
        for (size_t i = lo; i < hi; ++i) {
          const float m = inv_diag[i];
          for (size_t c = 0; c < 3; ++c) {
            const size_t k = 3 * i + c;
            x[k] += step[c] * p[k];
            const float ri = r[k] - step[c] * q[k];
            r[k] = ri;
            acc.v[c] += double(ri) * double(m * ri);
            acc.v[3 + c] += double(ri) * double(ri);
          }
        }
        part_b[size_t(t)] = acc;
      }
      sync.arrive_and_wait();
      reduce(part_b, tot);
      float beta[3];
      for (int c = 0; c < 3; ++c) {
        beta[c] = active[c] && rz[c] > 0.0 ? float(tot[c] / rz[c]) : 0.0f;
        if (active[c]) {
          rz[c] = tot[c];
          rr[c] = tot[3 + c];
          active[c] = std::sqrt(rr[c]) > limit[c] && tot[6 + c] >= 0.0;
        }
      }
      // p = M^-1 r + beta p.
      for (size_t i = lo; i < hi; ++i) {
        const float m = inv_diag[i];
        for (size_t c = 0; c < 3; ++c) p[3 * i + c] = m * r[3 * i + c] + beta[c] * p[3 * i + c];
      }
      sync.arrive_and_wait();  // p complete before the next A p reads neighbours
      ++it;
    }
    if (t == 0) {
      stats.iterations = it;
      stats.converged = !(active[0] || active[1] || active[2]);
      double rel = 0.0;
      for (int c = 0; c < 3; ++c)
        rel = std::max(rel, bnorm2[c] > 0.0 ? std::sqrt(rr[c] / bnorm2[c]) : std::sqrt(rr[c]));
      stats.relative_residual = rel;
    }
  });
  return stats;
}

}  // namespace dp::reconstruct
