// A = H^T W H + alpha^2 P for the forward-difference grid kernel (problem.h), without
// index arrays: per pixel the weight of its dx row (to the right; 0 in the last column),
// of its dy row (downwards; 0 in the last row) and the diagonal. (A x)_i is the weighted
// 5-point stencil with Neumann boundaries (Bhat et al. 2008; Lehtinen et al. 2013, Eq. 8).
// Same operator as Laplacian on Kernel::forward_differences, faster: no neighbour lists,
// one Vec4 per pixel.
#pragma once

#include <vector>

#include "reconstruct/pcg.h"
#include "reconstruct/problem.h"

namespace dp::reconstruct {

class GridOperator final : public ChunkedOperator {
 public:
  GridOperator(int width, int height);

  // row_weights in the kernel's row order (dx rows, then dy rows; nullptr = all ones),
  // pixel_weights (nullptr = all ones), alpha >= 0. Also factors the preconditioner.
  void set_weights(const float* row_weights, const float* pixel_weights, float alpha, int threads);
  // One IRLS reweighting (solve.h, ALGORITHMS.md) at the image x: every dx, dy and
  // primal row gets 1 / (|e|_2 + reg), e its RGB residual (alpha (x_i - g_i) for primal
  // rows); the weights are normalized to mean 1 over all rows, multiplied by the user's
  // row / pixel weights (nullptr = 1), and set as by set_weights(). Same values as
  // computing them over the kernel's pairs, without the index arrays. Returns the sum of
  // the raw weights.
  double set_irls_weights(const Vec4* image, const std::vector<Rgb>& b, const Vec4* g, double reg, float alpha,
                          const float* user_rows, const float* user_pixels, int threads);
  // One IRLS reweighting as set_irls_weights() fused with the start of the CG that
  // follows (grid_irls.cpp; one pass over the image instead of six): the weights are left
  // unnormalized (the mean-1 normalization scales A and the right-hand side alike, so the
  // solution is the same) and the right-hand side rhs = H^T W b + alpha^2 P g is not
  // stored. Writes r = rhs - A x, z = r / d on the pixels with (x + y) even and 0 on the
  // others (the multigrid V-cycle's first red half-step, multigrid.h; z = nullptr: not
  // written, solve_l1 leaves it to the V-cycle: one stream less), and per image row
  // the sums of r.r and rhs.rhs (row_rr, row_bb: height() each). Sets the diagonal and its
  // inverse, not the incomplete Cholesky factor. Results do not depend on the thread
  // count. Returns the sum of the raw weights.
  double reweight_start(const Vec4* x, const std::vector<Rgb>& b, const Vec4* g, double reg, float alpha,
                        const float* user_rows, const float* user_pixels, Vec4* r, Vec4* z, Vec4d* row_rr,
                        Vec4d* row_bb, int threads);
  // Whether set_weights / set_irls_weights also factor the block incomplete Cholesky
  // preconditioner (default true; precondition()/update() need it). The multigrid
  // solver (multigrid.h) only needs the diagonal.
  void set_factor_preconditioner(bool on) { m_factor_ic = on; }
  // out = H^T W b + alpha^2 P g (sums in double).
  void rhs(const std::vector<Rgb>& b, const Vec4* g, Vec4* out, int threads) const;

  int width() const { return m_w; }
  int height() const { return m_h; }
  // Per pixel: weight of its dx row, its dy row (0 where absent), alpha^2 p_i, and the
  // diagonal of A (the multigrid hierarchy, multigrid.h, is built from these).
  const float* weights_x() const { return m_wx.data(); }
  const float* weights_y() const { return m_wy.data(); }
  const float* data_weights() const { return m_data.data(); }
  const float* diagonal() const { return m_diag.data(); }
  // 1 / diagonal (0 where the diagonal is 0).
  const float* inverse_diagonal() const { return m_inv_diag.data(); }
  size_t pixels() const override { return size_t(m_w) * size_t(m_h); }
  size_t chunks() const override { return m_chunk_rows.size() - 1; }
  size_t chunk_begin(size_t c) const override { return size_t(m_chunk_rows[c]) * size_t(m_w); }
  size_t scratch_size() const override { return 2 * size_t(m_w); }
  void apply(size_t c, const Vec4* in, Vec4* out) const override;
  void direction(size_t c, const Vec4* z, const Vec4* p_old, Vec4 beta, Vec4* p_new, Vec4* q, Vec4d& pq,
                 Vec4* scratch) const override;
  void precondition(size_t c, const Vec4* r, Vec4* z) const override;
  void update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z, Vec4d& rz,
              Vec4d& rr) const override;

 private:
  // Diagonal and block incomplete Cholesky factor from m_wx, m_wy, m_data.
  void factor(int threads);
  // out[0..w) = A in for image row y; up / down are rows y-1 / y+1 of `in` (ignored at
  // the image border).
  void stencil_row(int y, const Vec4* up, const Vec4* mid, const Vec4* down, Vec4* out) const;
  // Forward substitution (D + L) t = r for row y of a chunk starting at row y0.
  void forward_row(int y, int y0, const Vec4* r, Vec4* z) const;
  // Backward substitution (D + L^T) z = D t over the chunk; optional dots r.z, r.r.
  void backward(size_t c, const Vec4* r, Vec4* z, Vec4d* rz, Vec4d* rr) const;

  int m_w, m_h;
  std::vector<int> m_chunk_rows;
  std::vector<float> m_wx, m_wy;   // per pixel: weight of its dx / dy row (0 if absent)
  std::vector<float> m_data;       // alpha^2 p_i
  std::vector<float> m_diag;       // sum of the pixel's row weights + alpha^2 p_i
  std::vector<float> m_inv_diag;   // 1 / m_diag (0 where m_diag is 0)
  // Block incomplete Cholesky factor, scaled for short dependency chains in the
  // substitutions: 1/D_i; forward t_i = r_i/D_i + fx_i t_{i-1} + fy_i t_{i-w};
  // backward z_i = t_i + bx_i z_{i+1} + by_i z_{i+w} (zero across chunk borders).
  std::vector<float> m_inv_pivot, m_fx, m_fy, m_bx, m_by;
  bool m_factor_ic = true;
};

}  // namespace dp::reconstruct
