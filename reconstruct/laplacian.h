// The normal-equation operator of the weighted screened Poisson problem,
//     A = H^T W H + alpha^2 P        (Lehtinen et al. 2013, Eq. 8 normal equations;
//                                      Manzi et al. 2014, Sec. 3.5 / Eq. 8),
// stored as a weighted graph Laplacian over pixels in CSR form: pixel i has one entry
// per kernel row touching it (neighbour n, weight w_r), and
//     (A x)_i = (sum_r w_r + alpha^2 p_i) x_i - sum_r w_r x_n.
// For the forward-difference grid with W = P = 1 this is the 5-point Laplacian with
// Neumann boundaries plus alpha^2 (Bhat et al. 2008).
// apply()/rhs() take RGB interleaved floats (3 per pixel); the ChunkedOperator interface
// (pcg.h) takes Vec4 per pixel. The three channels share A.
// The Laplacian keeps a reference to the kernel, which must outlive it.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/image.h"
#include "reconstruct/pcg.h"
#include "reconstruct/problem.h"

namespace dp::reconstruct {

class Laplacian final : public ChunkedOperator {
 public:
  explicit Laplacian(const Kernel& kernel);

  // Sets W and P (nullptr = all ones) and alpha (>= 0; 0 gives the bare graph
  // Laplacian H^T W H). Recomputes the diagonal and the block incomplete Cholesky pivots.
  void set_weights(const float* row_weights, const float* pixel_weights, float alpha, int threads);

  // out[3*lo .. 3*hi) = (A in) for pixels [lo, hi).
  void apply(const float* in, float* out, size_t lo, size_t hi) const { apply_dot(in, out, lo, hi, nullptr); }
  // The same, and if dot != nullptr adds sum_i in_i * (A in)_i over [lo, hi) per channel
  // to dot[0..3) (CG's p.Ap fused into the operator pass: one sweep less per iteration).
  void apply_dot(const float* in, float* out, size_t lo, size_t hi, double* dot) const;
  // out = H^T W b + alpha^2 P g, the right-hand side of the normal equations.
  void rhs(const std::vector<Rgb>& b, const float* g, float* out, int threads) const;

  const Kernel& kernel() const { return m_kernel; }

  // ChunkedOperator: chunks of image rows; couplings to pixels outside a chunk are
  // dropped from its preconditioner block.
  size_t pixels() const override { return m_diag.size(); }
  size_t chunks() const override { return m_chunk_rows.size() - 1; }
  size_t chunk_begin(size_t c) const override { return size_t(m_chunk_rows[c]) * size_t(m_kernel.width()); }
  void apply(size_t c, const Vec4* in, Vec4* out) const override;
  void direction(size_t c, const Vec4* z, const Vec4* p_old, Vec4 beta, Vec4* p_new, Vec4* q, Vec4d& pq,
                 Vec4* scratch) const override;
  void precondition(size_t c, const Vec4* r, Vec4* z) const override;
  void update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z, Vec4d& rz,
              Vec4d& rr) const override;

 private:
  // z = M^-1 r on chunk c (block IC substitutions). With alpha != nullptr, first
  // x += alpha p and r -= alpha q pixel by pixel in the forward pass (r_update is then r
  // itself); with rz != nullptr, r.z and r.r are summed in the backward pass.
  void substitute(size_t c, const Vec4* alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r_update, const Vec4* r,
                  Vec4* z, Vec4d* rz, Vec4d* rr) const;

  const Kernel& m_kernel;
  // CSR row starts, pixels()+1 entries. A pixel's entries are grouped: neighbours in its
  // chunk before it (ascending), in its chunk after it (descending), then outside its
  // chunk (kernel row order); m_lower_end / m_inner_end mark the group ends. The nearest
  // neighbour comes last in each substitution, which shortens its dependency chain.
  std::vector<int64_t> m_offset;
  std::vector<int64_t> m_lower_end, m_inner_end;
  std::vector<int32_t> m_nbr;     // neighbour pixel of each entry
  std::vector<int32_t> m_row;     // kernel row of each entry
  std::vector<float> m_weight;    // w_r of each entry
  std::vector<int> m_chunk_rows;
  std::vector<float> m_diag, m_inv_pivot;
  float m_alpha2 = 0.0f;
  std::vector<float> m_pixel_weight;  // empty = 1
};

// Runs fn(t) for t in [0, threads) on `threads` threads (the caller is thread 0).
// Exceptions are rethrown on the caller after all threads joined.
void run_team(int threads, const std::function<void(int)>& fn);
// Static partition of [0, n) into `parts` contiguous ranges: start of part t.
inline size_t part_begin(size_t n, int parts, int t) { return n * size_t(t) / size_t(parts); }
// Resolves 0 (= all hardware threads) and clamps to [1, hardware threads].
int resolve_threads(int threads);

}  // namespace dp::reconstruct
