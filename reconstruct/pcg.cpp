#include "reconstruct/pcg.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/error.h"
#include "reconstruct/laplacian.h"

namespace dp::reconstruct {

std::vector<int> row_chunks(int height, int rows) {
  rows = std::max(rows, 1);
  std::vector<int> out;
  const int count = std::max(1, (height + rows / 2) / rows);
  for (int c = 0; c <= count; ++c) out.push_back(int(int64_t(height) * c / count));
  return out;
}

void ChunkedOperator::update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z,
                             Vec4d& rz, Vec4d& rr) const {
  const size_t lo = chunk_begin(c), hi = chunk_begin(c + 1);
  for (size_t i = lo; i < hi; ++i) {
    x[i] += alpha * p[i];
    r[i] -= alpha * q[i];
  }
  precondition(c, r, z);
  for (size_t i = lo; i < hi; ++i) {
    accumulate(rz, r[i] * z[i]);
    accumulate(rr, r[i] * r[i]);
  }
}

namespace {

// Per-chunk partial sums, one cache line apart.
struct alignas(64) Partial {
  Vec4d a, b, c;
};

}  // namespace

CgStats pcg(const ChunkedOperator& A, const Vec4* rhs, Vec4* x, const CgSettings& settings, CgWorkspace* workspace) {
  DP_CHECK(settings.max_iterations >= 0, "max_iterations must be >= 0");
  const size_t n = A.pixels(), nc = A.chunks();
  DP_CHECK(nc > 0 && nc < (size_t(1) << 31), "pcg: bad chunk count");
  const int threads = int(std::max<size_t>(1, std::min<size_t>(size_t(resolve_threads(settings.threads)), nc)));
  const Vec4 zero = {};
  CgWorkspace local;
  CgWorkspace& ws = workspace ? *workspace : local;
  for (std::vector<Vec4>* v : {&ws.r, &ws.z, &ws.q, &ws.pa, &ws.pb}) v->resize(n);
  ws.scratch.resize(A.scratch_size() * size_t(threads));
  std::vector<Vec4>& r = ws.r;
  std::vector<Vec4>& z = ws.z;
  std::vector<Vec4>& q = ws.q;
  std::vector<Partial> part(nc);

  // Phases: 0 = init (r = rhs - A x, z = M^-1 r), then odd = A, even = B (pcg.h).
  // There is no barrier: `claim` holds (phase << 32 | next unclaimed chunk); the thread
  // that completes the last chunk of a phase does the reduction and publishes the next
  // phase. A thread that is descheduled while holding no chunk delays nobody, and one
  // that wakes up late just joins the current phase.
  std::atomic<uint64_t> claim{0};
  std::atomic<size_t> done{0};
  std::atomic<bool> finished{false};
  // Shared CG scalars: written only by the completing thread before it publishes the
  // next phase, read by workers only after they claimed a chunk of that phase.
  Vec4* p_old = ws.pa.data();
  Vec4* p_new = ws.pb.data();
  Vec4 alpha = zero, beta = zero;
  double rz[3] = {}, rr[3] = {}, bb[3] = {}, limit[3] = {};
  bool active[3] = {false, false, false};
  int it = 0;

  const auto sum = [&](Vec4d Partial::*field) {
    Vec4d s;
    for (const Partial& p : part) s += p.*field;  // chunk order: deterministic
    return s;
  };
  const auto complete = [&](uint64_t ph) {
    bool go = true;
    if (ph % 2 == 0) {  // init or B: new r.z and r.r
      const Vec4d s_rz = sum(&Partial::a), s_rr = sum(&Partial::b);
      if (ph == 0) {
        const Vec4d s_bb = sum(&Partial::c);
        for (int c = 0; c < 3; ++c) {
          rz[c] = s_rz[c];
          rr[c] = s_rr[c];
          bb[c] = s_bb[c];
          // An all-zero right-hand side has the solution 0: stop at a tiny absolute residual.
          limit[c] = settings.tolerance * std::sqrt(std::max(bb[c], 1e-60));
          active[c] = std::sqrt(rr[c]) > limit[c];
        }
        beta = zero;
      } else {
        for (int c = 0; c < 3; ++c) {
          beta[c] = active[c] && rz[c] > 0.0 ? float(s_rz[c] / rz[c]) : 0.0f;
          if (!active[c]) continue;
          rz[c] = s_rz[c];
          rr[c] = s_rr[c];
          active[c] = std::sqrt(rr[c]) > limit[c];
        }
        std::swap(p_old, p_new);
        ++it;
      }
      go = it < settings.max_iterations && (active[0] || active[1] || active[2]);
    } else {  // A: step sizes from p.Ap
      const Vec4d pq = sum(&Partial::a);
      for (int c = 0; c < 3; ++c) alpha[c] = active[c] && pq[c] > 0.0 ? float(rz[c] / pq[c]) : 0.0f;
    }
    done.store(0, std::memory_order_relaxed);
    if (!go) finished.store(true, std::memory_order_release);
    claim.store((ph + 1) << 32, std::memory_order_release);
    claim.notify_all();
  };

  const auto run_chunk = [&](uint64_t ph, size_t c, Vec4* tmp) {
    Partial acc;
    if (ph == 0) {
      const size_t lo = A.chunk_begin(c), hi = A.chunk_begin(c + 1);
      A.apply(c, x, q.data());
      for (size_t i = lo; i < hi; ++i) {
        r[i] = rhs[i] - q[i];
        p_old[i] = zero;  // beta = 0 in the first step; no stale NaN from a reused workspace
      }
      A.precondition(c, r.data(), z.data());
      for (size_t i = lo; i < hi; ++i) {
        accumulate(acc.a, r[i] * z[i]);
        accumulate(acc.b, r[i] * r[i]);
        accumulate(acc.c, rhs[i] * rhs[i]);
      }
    } else if (ph % 2 == 1) {
      A.direction(c, z.data(), p_old, beta, p_new, q.data(), acc.a, tmp);
    } else {
      A.update(c, alpha, p_new, q.data(), x, r.data(), z.data(), acc.a, acc.b);
    }
    part[c] = acc;
  };

  constexpr uint64_t kMask = 0xffffffffu;
  run_team(threads, [&](int t) {
    Vec4* tmp = ws.scratch.data() + A.scratch_size() * size_t(t);
    for (;;) {
      uint64_t w = claim.load(std::memory_order_acquire);
      if (finished.load(std::memory_order_acquire)) return;
      const uint64_t ph = w >> 32;
      while ((w >> 32) == ph && (w & kMask) < nc) {
        if (!claim.compare_exchange_weak(w, w + 1, std::memory_order_acq_rel, std::memory_order_acquire)) continue;
        run_chunk(ph, size_t(w & kMask), tmp);
        if (done.fetch_add(1, std::memory_order_acq_rel) + 1 == nc) complete(ph);
        w = claim.load(std::memory_order_acquire);
      }
      // Every chunk of this phase is claimed: sleep until the next phase is published.
      if ((w >> 32) == ph) claim.wait(w, std::memory_order_acquire);
    }
  });

  return cg_stats(it, active, rr, bb);
}

}  // namespace dp::reconstruct
