#include "reconstruct/grid_operator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "reconstruct/laplacian.h"

namespace dp::reconstruct {


GridOperator::GridOperator(int width, int height)
    : m_w(width), m_h(height), m_chunk_rows(row_chunks(height, kChunkRows)) {
  DP_CHECK(width > 0 && height > 0, "GridOperator: empty image");
  const size_t n = pixels();
  m_wx.assign(n, 0.0f);
  m_wy.assign(n, 0.0f);
  m_data.assign(n, 0.0f);
  m_diag.assign(n, 0.0f);
  m_inv_diag.assign(n, 0.0f);
  m_inv_pivot.assign(n, 0.0f);
  m_fx.assign(n, 0.0f);
  m_fy.assign(n, 0.0f);
  m_bx.assign(n, 0.0f);
  m_by.assign(n, 0.0f);
}

void GridOperator::set_weights(const float* row_weights, const float* pixel_weights, float alpha, int threads) {
  DP_CHECK(alpha >= 0.0f, "alpha must be >= 0");
  const float alpha2 = alpha * alpha;
  const int w = m_w, h = m_h;
  const size_t dy0 = size_t(h) * size_t(w - 1);  // first dy row of the kernel
  threads = resolve_threads(threads);
  run_team(threads, [&](int t) {
    for (int y = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1)); y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const size_t rx = size_t(y) * size_t(w - 1) + size_t(x), ry = dy0 + i;
        m_wx[i] = x + 1 < w ? (row_weights ? row_weights[rx] : 1.0f) : 0.0f;
        m_wy[i] = y + 1 < h ? (row_weights ? row_weights[ry] : 1.0f) : 0.0f;
        m_data[i] = alpha2 * (pixel_weights ? pixel_weights[i] : 1.0f);
      }
  });
  factor(threads);
}

double GridOperator::set_irls_weights(const Vec4* image, const std::vector<Rgb>& b, const Vec4* g, double reg,
                                      float alpha, const float* user_rows, const float* user_pixels, int threads) {
  DP_CHECK(alpha >= 0.0f, "alpha must be >= 0");
  const int w = m_w, h = m_h;
  DP_CHECK(b.size() == size_t(h) * size_t(w - 1) + size_t(w) * size_t(h - 1), "b size mismatch");
  const size_t dy0 = size_t(h) * size_t(w - 1), n = pixels();
  threads = resolve_threads(threads);
  struct alignas(64) Sum {
    double v = 0.0;
  };
  std::vector<Sum> sums(size_t(threads), Sum{});
  // Raw weights 1 / (|e|_2 + reg) of every row, e its RGB residual (in double).
  const auto raw = [reg](double e0, double e1, double e2) {
    return 1.0 / (std::sqrt(e0 * e0 + e1 * e1 + e2 * e2) + reg);
  };
  run_team(threads, [&](int t) {
    double s = 0.0;
    for (int y = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1)); y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const Vec4 xi = image[i];
        float wx = 0.0f, wy = 0.0f;
        if (x + 1 < w) {
          const Rgb& d = b[size_t(y) * size_t(w - 1) + size_t(x)];
          const Vec4 xj = image[i + 1];
          const double v = raw(double(xj[0]) - double(xi[0]) - double(d[0]),
                               double(xj[1]) - double(xi[1]) - double(d[1]), double(xj[2]) - double(xi[2]) - double(d[2]));
          wx = float(v);
          s += v;
        }
        if (y + 1 < h) {
          const Rgb& d = b[dy0 + i];
          const Vec4 xj = image[i + size_t(w)];
          const double v = raw(double(xj[0]) - double(xi[0]) - double(d[0]),
                               double(xj[1]) - double(xi[1]) - double(d[1]), double(xj[2]) - double(xi[2]) - double(d[2]));
          wy = float(v);
          s += v;
        }
        const double a = double(alpha);
        const double wp = raw(a * (double(xi[0]) - double(g[i][0])), a * (double(xi[1]) - double(g[i][1])),
                              a * (double(xi[2]) - double(g[i][2])));
        s += wp;
        m_wx[i] = wx;
        m_wy[i] = wy;
        m_data[i] = float(wp);
      }
    sums[size_t(t)].v = s;
  });
  double total = 0.0;
  for (const Sum& s : sums) total += s.v;
  // Normalized to mean 1 over all rows (gradient and primal), then the user's weights.
  const float scale = float(double(b.size() + n) / total);
  const float alpha2 = alpha * alpha;
  run_team(threads, [&](int t) {
    for (int y = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1)); y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        if (x + 1 < w) m_wx[i] *= scale * (user_rows ? user_rows[size_t(y) * size_t(w - 1) + size_t(x)] : 1.0f);
        if (y + 1 < h) m_wy[i] *= scale * (user_rows ? user_rows[dy0 + i] : 1.0f);
        m_data[i] = alpha2 * (m_data[i] * (scale * (user_pixels ? user_pixels[i] : 1.0f)));
      }
  });
  factor(threads);
  return total;
}

void GridOperator::factor(int threads) {
  const int w = m_w;
  threads = resolve_threads(threads);
  // Diagonal, then the block incomplete Cholesky pivots chunk by chunk: with L the
  // strictly lower part of the chunk's block, D_i = A_ii - sum_{j < i} A_ij^2 / D_j over
  // the (at most two) lower neighbours in the block (zero fill for the 5-point stencil).
  const int nc = int(chunks());
  run_team(std::min(threads, nc), [&](int t) {
    for (int c = t; c < nc; c += std::min(threads, nc)) {
      const int y0 = m_chunk_rows[size_t(c)], y1 = m_chunk_rows[size_t(c) + 1];
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = size_t(y) * size_t(w) + size_t(x);
          double d = double(m_data[i]) + double(m_wx[i]) + double(m_wy[i]);
          if (x > 0) d += double(m_wx[i - 1]);
          if (y > 0) d += double(m_wy[i - size_t(w)]);
          m_diag[i] = float(d);
          m_inv_diag[i] = m_diag[i] > 0.0f ? 1.0f / m_diag[i] : 0.0f;
          if (!m_factor_ic) continue;
          double piv = double(m_diag[i]);
          // (Modified IC, which also subtracts the dropped fill, needed more CG iterations
          // in IRLS: plain IC(0).)
          if (x > 0) piv -= double(m_wx[i - 1]) * double(m_wx[i - 1]) * double(m_inv_pivot[i - 1]);
          if (y > y0) piv -= double(m_wy[i - size_t(w)]) * double(m_wy[i - size_t(w)]) * double(m_inv_pivot[i - size_t(w)]);
          // Positive in exact arithmetic (M-matrix); guard against round-off anyway.
          if (!(piv > 1e-6 * d)) piv = d;
          const float ip = piv > 0.0 ? float(1.0 / piv) : 0.0f;
          m_inv_pivot[i] = ip;
          m_fx[i] = x > 0 ? m_wx[i - 1] * ip : 0.0f;
          m_fy[i] = y > y0 ? m_wy[i - size_t(w)] * ip : 0.0f;
          m_bx[i] = m_wx[i] * ip;
          m_by[i] = y + 1 < y1 ? m_wy[i] * ip : 0.0f;
        }
    }
  });
}

void GridOperator::rhs(const std::vector<Rgb>& b, const Vec4* g, Vec4* out, int threads) const {
  const int w = m_w, h = m_h;
  DP_CHECK(b.size() == size_t(h) * size_t(w - 1) + size_t(w) * size_t(h - 1), "b size mismatch");
  const size_t dy0 = size_t(h) * size_t(w - 1);
  threads = resolve_threads(threads);
  run_team(threads, [&](int t) {
    for (int y = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1)); y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        // (H^T W b)_i = w dx(x-1,y) - w dx(x,y) + w dy(x,y-1) - w dy(x,y), absent rows omitted.
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const size_t rx = size_t(y) * size_t(w - 1) + size_t(x), ry = dy0 + i;
        Rgbd acc = double(m_data[i]) * Rgbd(double(g[i][0]), double(g[i][1]), double(g[i][2]));
        if (x > 0) acc += double(m_wx[i - 1]) * b[rx - 1].cast<double>();
        if (x + 1 < w) acc -= double(m_wx[i]) * b[rx].cast<double>();
        if (y > 0) acc += double(m_wy[i - size_t(w)]) * b[ry - size_t(w)].cast<double>();
        if (y + 1 < h) acc -= double(m_wy[i]) * b[ry].cast<double>();
        out[i] = Vec4{float(acc[0]), float(acc[1]), float(acc[2]), 0.0f};
      }
  });
}

void GridOperator::stencil_row(int y, const Vec4* up, const Vec4* mid, const Vec4* down, Vec4* out) const {
  const int w = m_w;
  const size_t base = size_t(y) * size_t(w);
  const float* wx = m_wx.data() + base;
  const float* wy = m_wy.data() + base;
  const float* dg = m_diag.data() + base;
  const float* wu = y > 0 ? m_wy.data() + base - size_t(w) : nullptr;
  const auto vertical = [&](int x, Vec4 a) {
    if (wu) a -= wu[x] * up[x];
    if (y + 1 < m_h) a -= wy[x] * down[x];
    return a;
  };
  if (w == 1) {
    out[0] = vertical(0, dg[0] * mid[0]);
    return;
  }
  out[0] = vertical(0, dg[0] * mid[0] - wx[0] * mid[1]);
  if (wu && y + 1 < m_h) {
    for (int x = 1; x + 1 < w; ++x)
      out[x] = dg[x] * mid[x] - wx[x - 1] * mid[x - 1] - wx[x] * mid[x + 1] - wu[x] * up[x] - wy[x] * down[x];
  } else {
    for (int x = 1; x + 1 < w; ++x) out[x] = vertical(x, dg[x] * mid[x] - wx[x - 1] * mid[x - 1] - wx[x] * mid[x + 1]);
  }
  out[w - 1] = vertical(w - 1, dg[w - 1] * mid[w - 1] - wx[w - 2] * mid[w - 2]);
}

void GridOperator::apply(size_t c, const Vec4* in, Vec4* out) const {
  const size_t w = size_t(m_w);
  for (int y = m_chunk_rows[c]; y < m_chunk_rows[c + 1]; ++y) {
    const Vec4* mid = in + size_t(y) * w;
    stencil_row(y, y > 0 ? mid - w : nullptr, mid, y + 1 < m_h ? mid + w : nullptr, out + size_t(y) * w);
  }
}

void GridOperator::direction(size_t c, const Vec4* z, const Vec4* p_old, Vec4 beta, Vec4* p_new, Vec4* q, Vec4d& pq,
                             Vec4* scratch) const {
  const size_t w = size_t(m_w);
  const int y0 = m_chunk_rows[c], y1 = m_chunk_rows[c + 1];
  const auto form = [&](int y, Vec4* dst) {
    const size_t base = size_t(y) * w;
    for (size_t x = 0; x < w; ++x) dst[x] = z[base + x] + beta * p_old[base + x];
  };
  // Rows y0-1 and y1 belong to other chunks: formed here into scratch (their owners
  // write the same values into p_new concurrently).
  Vec4* halo_up = scratch;
  Vec4* halo_down = scratch + w;
  if (y0 > 0) form(y0 - 1, halo_up);
  form(y0, p_new + size_t(y0) * w);
  for (int y = y0; y < y1; ++y) {
    Vec4* mid = p_new + size_t(y) * w;
    const Vec4* down = nullptr;
    if (y + 1 < y1) {
      form(y + 1, mid + w);
      down = mid + w;
    } else if (y + 1 < m_h) {
      form(y + 1, halo_down);
      down = halo_down;
    }
    const Vec4* up = y == 0 ? nullptr : y == y0 ? halo_up : mid - w;
    Vec4* out = q + size_t(y) * w;
    stencil_row(y, up, mid, down, out);
    Vec4d s = pq;
    for (size_t x = 0; x < w; ++x) accumulate(s, mid[x] * out[x]);
    pq = s;
  }
}

void GridOperator::forward_row(int y, int y0, const Vec4* r, Vec4* z) const {
  const size_t w = size_t(m_w), base = size_t(y) * w;
  const float* ip = m_inv_pivot.data() + base;
  const float* fx = m_fx.data() + base;
  const float* fy = m_fy.data() + base;
  const Vec4* rr = r + base;
  Vec4* zz = z + base;
  Vec4 left = {};
  // The only dependency chain is through `left`: one multiply and one add per pixel.
  if (y == y0) {
    for (size_t x = 0; x < w; ++x) zz[x] = left = rr[x] * ip[x] + fx[x] * left;
  } else {
    const Vec4* up = zz - w;
    for (size_t x = 0; x < w; ++x) zz[x] = left = (rr[x] * ip[x] + fy[x] * up[x]) + fx[x] * left;
  }
}

void GridOperator::backward(size_t c, const Vec4* r, Vec4* z, Vec4d* rz, Vec4d* rr) const {
  const size_t w = size_t(m_w);
  const int y0 = m_chunk_rows[c], y1 = m_chunk_rows[c + 1];
  for (int y = y1 - 1; y >= y0; --y) {
    const size_t base = size_t(y) * w;
    const float* bx = m_bx.data() + base;
    const float* by = m_by.data() + base;
    Vec4* zz = z + base;
    Vec4 right = {};
    if (y + 1 == y1) {
      for (size_t x = w; x-- > 0;) zz[x] = right = zz[x] + bx[x] * right;
    } else {
      const Vec4* down = zz + w;
      for (size_t x = w; x-- > 0;) zz[x] = right = (zz[x] + by[x] * down[x]) + bx[x] * right;
    }
    if (rz) {
      const Vec4* rrow = r + base;
      Vec4d srz = *rz, srr = *rr;
      for (size_t x = 0; x < w; ++x) {
        accumulate(srz, rrow[x] * zz[x]);
        accumulate(srr, rrow[x] * rrow[x]);
      }
      *rz = srz;
      *rr = srr;
    }
  }
}

void GridOperator::precondition(size_t c, const Vec4* r, Vec4* z) const {
  // Solve (D + L) t = r, then (D + L^T) z = D t, within the chunk.
  const int y0 = m_chunk_rows[c], y1 = m_chunk_rows[c + 1];
  for (int y = y0; y < y1; ++y) forward_row(y, y0, r, z);
  backward(c, r, z, nullptr, nullptr);
}

void GridOperator::update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z, Vec4d& rz,
                          Vec4d& rr) const {
  // Row by row: the updated residual row is still in cache for the forward substitution.
  const size_t w = size_t(m_w);
  const int y0 = m_chunk_rows[c], y1 = m_chunk_rows[c + 1];
  for (int y = y0; y < y1; ++y) {
    const size_t base = size_t(y) * w;
    for (size_t i = base; i < base + w; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    forward_row(y, y0, r, z);
  }
  backward(c, r, z, &rz, &rr);
}

}  // namespace dp::reconstruct
