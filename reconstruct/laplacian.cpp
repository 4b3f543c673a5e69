#include "reconstruct/laplacian.h"

#include <algorithm>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "core/thread_pool.h"

namespace dp::reconstruct {

void run_team(int threads, const std::function<void(int)>& fn) {
  if (threads <= 1) {
    fn(0);
    return;
  }
  std::exception_ptr error;
  std::mutex error_mutex;
  auto guarded = [&](int t) {
    try {
      fn(t);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(size_t(threads - 1));
  for (int t = 1; t < threads; ++t) pool.emplace_back(guarded, t);
  guarded(0);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

int resolve_threads(int threads) {
  const int hw = core::hardware_threads();
  if (threads <= 0) return hw;
  return std::min(threads, std::max(hw, 1));
}


Laplacian::Laplacian(const Kernel& kernel) : m_kernel(kernel), m_chunk_rows(row_chunks(kernel.height(), kChunkRows)) {
  const size_t n = kernel.pixels();
  const auto& pairs = kernel.pairs();
  m_offset.assign(n + 1, 0);
  for (const PixelPair& p : pairs) {
    ++m_offset[size_t(p.i) + 1];
    ++m_offset[size_t(p.j) + 1];
  }
  for (size_t i = 0; i < n; ++i) m_offset[i + 1] += m_offset[i];
  const size_t entries = size_t(m_offset[n]);
  m_nbr.resize(entries);
  m_row.resize(entries);
  m_weight.assign(entries, 1.0f);
  std::vector<int64_t> fill(m_offset.begin(), m_offset.end() - 1);
  // Rows are visited in order, so each pixel's entries are sorted by row index: the
  // operator (and every reduction over it) is deterministic.
  for (size_t r = 0; r < pairs.size(); ++r) {
    const PixelPair& p = pairs[r];
    const int64_t ei = fill[size_t(p.i)]++, ej = fill[size_t(p.j)]++;
    m_nbr[size_t(ei)] = p.j;
    m_row[size_t(ei)] = int32_t(r);
    m_nbr[size_t(ej)] = p.i;
    m_row[size_t(ej)] = int32_t(r);
  }
  // Group and order each pixel's entries (ties in the neighbour keep kernel row order).
  m_lower_end.resize(n);
  m_inner_end.resize(n);
  std::vector<std::pair<int32_t, int32_t>> tmp;  // (neighbour, kernel row)
  for (size_t c = 0; c < chunks(); ++c) {
    const size_t lo = chunk_begin(c), hi = chunk_begin(c + 1);
    for (size_t i = lo; i < hi; ++i) {
      tmp.clear();
      for (int64_t e = m_offset[i]; e < m_offset[i + 1]; ++e) tmp.emplace_back(m_nbr[size_t(e)], m_row[size_t(e)]);
      const auto group = [&](const std::pair<int32_t, int32_t>& a) {
        const size_t nb = size_t(a.first);
        return nb >= lo && nb < hi ? (nb < i ? 0 : 1) : 2;
      };
      std::stable_sort(tmp.begin(), tmp.end(), [&](const auto& a, const auto& b) {
        const int ga = group(a), gb = group(b);
        if (ga != gb) return ga < gb;
        if (ga == 0) return a.first < b.first;
        if (ga == 1) return a.first > b.first;
        return false;
      });
      int64_t e = m_offset[i];
      m_lower_end[i] = m_inner_end[i] = e;
      for (const auto& a : tmp) {
        m_nbr[size_t(e)] = a.first;
        m_row[size_t(e)] = a.second;
        ++e;
        if (group(a) == 0) m_lower_end[i] = e;
        if (group(a) <= 1) m_inner_end[i] = e;
      }
    }
  }
  m_diag.assign(n, 0.0f);
  m_inv_pivot.assign(n, 0.0f);
}

void Laplacian::set_weights(const float* row_weights, const float* pixel_weights, float alpha, int threads) {
  DP_CHECK(alpha >= 0.0f, "alpha must be >= 0");
  m_alpha2 = alpha * alpha;
  const size_t n = pixels();
  if (pixel_weights)
    m_pixel_weight.assign(pixel_weights, pixel_weights + n);
  else
    m_pixel_weight.clear();
  // Per chunk: weights and diagonal, then the block incomplete Cholesky pivots
  // D_i = A_ii - sum_e w_e^2 / D_n over the entries e of pixel i whose neighbour n is in
  // the chunk and before i (zero fill; a pair listed twice counts as two entries, which
  // only makes D larger: still SPD).
  const int nc = int(chunks());
  threads = std::min(resolve_threads(threads), nc);
  run_team(threads, [&](int t) {
    for (int c = t; c < nc; c += threads) {
      const size_t lo = chunk_begin(size_t(c)), hi = chunk_begin(size_t(c) + 1);
      for (size_t i = lo; i < hi; ++i) {
        double d = double(m_alpha2) * (pixel_weights ? double(pixel_weights[i]) : 1.0);
        for (int64_t e = m_offset[i]; e < m_offset[i + 1]; ++e) {
          const float w = row_weights ? row_weights[m_row[size_t(e)]] : 1.0f;
          m_weight[size_t(e)] = w;
          d += double(w);
        }
        m_diag[i] = float(d);
        double piv = double(m_diag[i]);
        for (int64_t e = m_offset[i]; e < m_lower_end[i]; ++e) {
          const size_t nb = size_t(m_nbr[size_t(e)]);
          piv -= double(m_weight[size_t(e)]) * double(m_weight[size_t(e)]) * double(m_inv_pivot[nb]);
        }
        // Positive in exact arithmetic (M-matrix); guard against round-off anyway.
        if (!(piv > 1e-6 * d)) piv = d;
        m_inv_pivot[i] = piv > 0.0 ? float(1.0 / piv) : 0.0f;
      }
    }
  });
}

void Laplacian::apply(size_t c, const Vec4* in, Vec4* out) const {
  const int64_t* off = m_offset.data();
  const int32_t* nbr = m_nbr.data();
  const float* wt = m_weight.data();
  for (size_t i = chunk_begin(c), hi = chunk_begin(c + 1); i < hi; ++i) {
    Vec4 a = m_diag[i] * in[i];
    for (int64_t e = off[i], end = off[i + 1]; e < end; ++e) a -= wt[e] * in[nbr[e]];
    out[i] = a;
  }
}

void Laplacian::direction(size_t c, const Vec4* z, const Vec4* p_old, Vec4 beta, Vec4* p_new, Vec4* q, Vec4d& pq,
                          Vec4*) const {
  const int64_t* off = m_offset.data();
  const int32_t* nbr = m_nbr.data();
  const float* wt = m_weight.data();
  const size_t lo = chunk_begin(c), hi = chunk_begin(c + 1);
  for (size_t i = lo; i < hi; ++i) p_new[i] = z[i] + beta * p_old[i];
  for (size_t i = lo; i < hi; ++i) {
    Vec4 a = m_diag[i] * p_new[i];
    const int64_t inner = m_inner_end[i];
    for (int64_t e = off[i]; e < inner; ++e) a -= wt[e] * p_new[nbr[e]];
    // Neighbours in other chunks: their p_new is being written by another thread; form
    // the same value from z and p_old, which nobody writes in this phase.
    for (int64_t e = inner, end = off[i + 1]; e < end; ++e) {
      const size_t nb = size_t(nbr[e]);
      a -= wt[e] * (z[nb] + beta * p_old[nb]);
    }
    q[i] = a;
    accumulate(pq, p_new[i] * a);
  }
}

void Laplacian::precondition(size_t c, const Vec4* r, Vec4* z) const {
  substitute(c, nullptr, nullptr, nullptr, nullptr, nullptr, r, z, nullptr, nullptr);
}

void Laplacian::update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z, Vec4d& rz,
                       Vec4d& rr) const {
  substitute(c, &alpha, p, q, x, r, r, z, &rz, &rr);
}

void Laplacian::substitute(size_t c, const Vec4* alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r_update,
                           const Vec4* r, Vec4* z, Vec4d* rz, Vec4d* rr) const {
  // Solve (D + L) t = r, then (D + L^T) z = D t, within the chunk; A_ij = -w.
  const int64_t* off = m_offset.data();
  const int32_t* nbr = m_nbr.data();
  const float* ip = m_inv_pivot.data();
  const size_t lo = chunk_begin(c), hi = chunk_begin(c + 1);
  const int64_t* lower_end = m_lower_end.data();
  const int64_t* inner_end = m_inner_end.data();
  const float* wt = m_weight.data();
  // The entry of the adjacent pixel (i-1 forward, i+1 backward) comes last in its group
  // when present; its value is kept in a register instead of being reloaded from the
  // store just made, which would put a store-to-load forward on the dependency chain.
  Vec4 prev = {};
  for (size_t i = lo; i < hi; ++i) {
    int64_t end = lower_end[i];
    float w_prev = 0.0f;
    if (end > off[i] && size_t(nbr[end - 1]) + 1 == i) w_prev = wt[--end];
    if (alpha) {
      x[i] += *alpha * p[i];
      r_update[i] -= *alpha * q[i];  // r_update == r
    }
    Vec4 t = r[i];
    for (int64_t e = off[i]; e < end; ++e) t += wt[e] * z[nbr[e]];
    prev = t * ip[i] + (w_prev * ip[i]) * prev;
    z[i] = prev;
  }
  prev = Vec4{};
  Vec4d sum_rz, sum_rr;
  for (size_t i = hi; i-- > lo;) {
    int64_t end = inner_end[i];
    float w_prev = 0.0f;
    if (end > lower_end[i] && size_t(nbr[end - 1]) == i + 1) w_prev = wt[--end];
    Vec4 s = {};
    for (int64_t e = lower_end[i]; e < end; ++e) s += wt[e] * z[nbr[e]];
    prev = (z[i] + s * ip[i]) + (w_prev * ip[i]) * prev;
    z[i] = prev;
    if (rz) {
      accumulate(sum_rz, r[i] * prev);
      accumulate(sum_rr, r[i] * r[i]);
    }
  }
  if (rz) {
    *rz += sum_rz;
    *rr += sum_rr;
  }
}

void Laplacian::apply_dot(const float* in, float* out, size_t lo, size_t hi, double* dot) const {
  const int64_t* off = m_offset.data();
  const int32_t* nbr = m_nbr.data();
  const float* wt = m_weight.data();
  double d0 = 0.0, d1 = 0.0, d2 = 0.0;
  for (size_t i = lo; i < hi; ++i) {
    const float d = m_diag[i];
    const float x0 = in[3 * i], x1 = in[3 * i + 1], x2 = in[3 * i + 2];
    float a0 = d * x0, a1 = d * x1, a2 = d * x2;
    for (int64_t e = off[i], end = off[i + 1]; e < end; ++e) {
      const float w = wt[e];
      const float* v = in + 3 * size_t(nbr[e]);
      a0 -= w * v[0];
      a1 -= w * v[1];
      a2 -= w * v[2];
    }
    out[3 * i] = a0;
    out[3 * i + 1] = a1;
    out[3 * i + 2] = a2;
    d0 += double(x0 * a0);
    d1 += double(x1 * a1);
    d2 += double(x2 * a2);
  }
  if (dot) {
    dot[0] += d0;
    dot[1] += d1;
    dot[2] += d2;
  }
}

void Laplacian::rhs(const std::vector<Rgb>& b, const float* g, float* out, int threads) const {
  DP_CHECK(b.size() == m_kernel.rows(), "b size mismatch");
  const size_t n = pixels();
  const auto& pairs = m_kernel.pairs();
  threads = resolve_threads(threads);
  run_team(threads, [&](int t) {
    const size_t lo = part_begin(n, threads, t), hi = part_begin(n, threads, t + 1);
    for (size_t i = lo; i < hi; ++i) {
      // (H^T W b)_i: +w_r b_r where i is the pair's j, -w_r b_r where it is the pair's i.
      const double s = double(m_alpha2) * (m_pixel_weight.empty() ? 1.0 : double(m_pixel_weight[i]));
      double a[3] = {s * double(g[3 * i]), s * double(g[3 * i + 1]), s * double(g[3 * i + 2])};
      for (int64_t e = m_offset[i]; e < m_offset[i + 1]; ++e) {
        const int32_t r = m_row[size_t(e)];
        const double w = double(m_weight[size_t(e)]);
        const double sign = size_t(pairs[size_t(r)].j) == i ? 1.0 : -1.0;
        for (int c = 0; c < 3; ++c) a[c] += sign * w * double(b[size_t(r)][c]);
      }
      for (int c = 0; c < 3; ++c) out[3 * i + size_t(c)] = float(a[c]);
    }
  });
}

}  // namespace dp::reconstruct
