// GridOperator::reweight_start (grid_operator.h): one IRLS reweighting fused with the
// start of the CG that follows, in one pass over the image (issue 18). Separate passes
// for the weights, their normalization, the diagonal, the right-hand side, the inverse
// diagonal and the CG's initial residual read the image arrays six times; the reweighting
// was ~30% of the L1 solve's time.
//
// Per image row: the residuals e of its dx, dy and primal rows in double (a weight
// 1 / (|e| + reg) with reg down to ~1e-7 needs e to better than float's rounding), their
// weights in a loop the compiler vectorizes (this file is built with -fno-math-errno, so
// sqrt needs no error branch), then the diagonal, the right-hand side and r = rhs - A x in
// float, as the separate passes did.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/laplacian.h"

namespace dp::reconstruct {

namespace {

// The three channels of v in double: lanes 0, 1 and lane 2 (with a 0).
struct Rgbd2 {
  Vec2d lo, hi;
};
inline Rgbd2 widen(Vec4 v) { return {Vec2d{double(v[0]), double(v[1])}, Vec2d{double(v[2]), 0.0}}; }
inline Rgbd2 widen(const Rgb& v) { return {Vec2d{double(v[0]), double(v[1])}, Vec2d{double(v[2]), 0.0}}; }
inline Vec4 to_vec(const Rgb& v) { return Vec4{v[0], v[1], v[2], 0.0f}; }

// |a - b - d|^2 in double.
inline double norm2(const Rgbd2& a, const Rgbd2& b, const Rgbd2& d) {
  const Vec2d lo = a.lo - b.lo - d.lo, hi = a.hi - b.hi - d.hi;
  const Vec2d s = lo * lo + hi * hi;
  return s[0] + s[1];
}

// raw[k] = 1 / (sqrt(e2[k]) + reg), vectorized.
void raw_weights(const double* e2, double* raw, size_t count, double reg) {
  for (size_t k = 0; k < count; ++k) raw[k] = 1.0 / (std::sqrt(e2[k]) + reg);
}

}  // namespace

double GridOperator::reweight_start(const Vec4* x, const std::vector<Rgb>& b, const Vec4* g, double reg, float alpha,
                                    const float* user_rows, const float* user_pixels, Vec4* r, Vec4* z,
                                    Vec4d* row_rr, Vec4d* row_bb, int threads) {
  DP_CHECK(alpha >= 0.0f, "alpha must be >= 0");
  const int w = m_w, h = m_h;
  DP_CHECK(b.size() == size_t(h) * size_t(w - 1) + size_t(w) * size_t(h - 1), "b size mismatch");
  const size_t W = size_t(w), dy0 = size_t(h) * (W - 1);
  const float alpha2 = alpha * alpha;
  const double a = double(alpha);
  threads = std::min(resolve_threads(threads), h);
  std::vector<double> row_sum(size_t(h), 0.0);
  // Per thread: e^2 and raw weights of one row (dx, dy, primal) in double; the weighted
  // gradients w b of the row's dx rows and of its dy rows and the dy rows above (Vec4).
  std::vector<double> scratch(size_t(threads) * 6 * W);
  std::vector<Vec4> fluxes(size_t(threads) * 3 * W);
  std::vector<float> above(size_t(threads) * W);

  run_team(threads, [&](int t) {
    const int y0 = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1));
    double* e2x = scratch.data() + size_t(t) * 6 * W;
    double* e2y = e2x + W;
    double* e2p = e2y + W;
    double* rx = e2p + W;
    double* ry = rx + W;
    double* rp = ry + W;
    Vec4* fx = fluxes.data() + size_t(t) * 3 * W;
    Vec4* fy = fx + W;
    Vec4* fy_up = fy + W;
    // dy weights of row y (y + 1 < h) into wy_out (user weights applied), their w b into
    // flux; raw values in ry.
    const auto dy_row = [&](int y, float* wy_out, Vec4* flux) {
      const size_t base = size_t(y) * W;
      for (size_t i = 0; i < W; ++i)
        e2y[i] = norm2(widen(x[base + i + W]), widen(x[base + i]), widen(b[dy0 + base + i]));
      raw_weights(e2y, ry, W, reg);
      for (size_t i = 0; i < W; ++i) {
        wy_out[i] = float(ry[i]) * (user_rows ? user_rows[dy0 + base + i] : 1.0f);
        flux[i] = wy_out[i] * to_vec(b[dy0 + base + i]);
      }
    };
    float* wy_above = above.data() + size_t(t) * W;
    if (y0 > 0)
      dy_row(y0 - 1, wy_above, fy_up);
    else
      std::fill(fy_up, fy_up + W, Vec4{});
    const Rgbd2 zero2 = {};
    for (int y = y0; y < y1; ++y) {
      const size_t base = size_t(y) * W, bx = size_t(y) * (W - 1);
      const Vec4* xr = x + base;
      const Vec4* gr = g + base;
      float* wx = m_wx.data() + base;
      float* wy = m_wy.data() + base;
      float* data = m_data.data() + base;
      // Weights of the row's dx, dy and primal rows: 1 / (|e|_2 + reg), then the user's.
      for (size_t i = 0; i + 1 < W; ++i) e2x[i] = norm2(widen(xr[i + 1]), widen(xr[i]), widen(b[bx + i]));
      for (size_t i = 0; i < W; ++i) e2p[i] = a * a * norm2(widen(xr[i]), widen(gr[i]), zero2);
      raw_weights(e2x, rx, W - 1, reg);
      raw_weights(e2p, rp, W, reg);
      double s = 0.0;
      for (size_t i = 0; i + 1 < W; ++i) {
        wx[i] = float(rx[i]) * (user_rows ? user_rows[bx + i] : 1.0f);
        fx[i] = wx[i] * to_vec(b[bx + i]);
        s += rx[i];
      }
      wx[W - 1] = 0.0f;
      fx[W - 1] = Vec4{};
      if (y + 1 < h) {
        dy_row(y, wy, fy);
        for (size_t i = 0; i < W; ++i) s += ry[i];
      } else {
        std::fill(wy, wy + W, 0.0f);
        std::fill(fy, fy + W, Vec4{});
      }
      for (size_t i = 0; i < W; ++i) {
        data[i] = alpha2 * (float(rp[i]) * (user_pixels ? user_pixels[base + i] : 1.0f));
        s += rp[i];
      }
      row_sum[size_t(y)] = s;

      // Diagonal, right-hand side H^T W b + alpha^2 P g, r = rhs - A x, the red half-step
      // and the row sums.
      const float* wu = y == 0 ? nullptr : y == y0 ? wy_above : m_wy.data() + base - W;
      const Vec4* up = y > 0 ? xr - w : nullptr;
      const Vec4* down = y + 1 < h ? xr + w : nullptr;
      float* dg = m_diag.data() + base;
      float* id = m_inv_diag.data() + base;
      Vec4d srr, sbb;
      const auto pixel = [&](size_t i) {
        float d = data[i] + wx[i] + wy[i];
        Vec4 f = data[i] * gr[i] - fx[i] - fy[i] + fy_up[i];
        Vec4 ax = -wx[i] * (i + 1 < W ? xr[i + 1] : Vec4{});
        if (i > 0) {
          d += wx[i - 1];
          f += fx[i - 1];
          ax -= wx[i - 1] * xr[i - 1];
        }
        if (wu) {
          d += wu[i];
          ax -= wu[i] * up[i];
        }
        if (down) ax -= wy[i] * down[i];
        dg[i] = d;
        id[i] = d > 0.0f ? 1.0f / d : 0.0f;
        const Vec4 ri = f - (d * xr[i] + ax);
        r[base + i] = ri;
        if (z) z[base + i] = ((i + size_t(y)) & 1) ? Vec4{} : ri * id[i];
        accumulate(srr, ri * ri);
        accumulate(sbb, f * f);
      };
      for (size_t i = 0; i < W; ++i) pixel(i);
      row_rr[y] = srr;
      row_bb[y] = sbb;
      std::swap(fy, fy_up);  // this row's dy fluxes are the next row's fluxes from above
    }
  });
  double total = 0.0;
  for (const double s : row_sum) total += s;
  return total;
}

}  // namespace dp::reconstruct
