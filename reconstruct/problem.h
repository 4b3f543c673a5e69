// Screened Poisson reconstruction problem (Lehtinen et al. 2013, Eq. 8; Manzi et al.
// 2014, Eq. 8): find the image I minimizing
//     sum_r w_r |(H I - b)_r|^p  +  alpha^2 sum_i p_i |I_i - I_g,i|^p,     p = 2 or 1,
// where each row r of H is one pixel pair (i, j) with (H I)_r = I_j - I_i, b_r is the
// sampled RGB difference for that pair, I_g the noisy primal image, w_r >= 0 optional
// per-row weights and p_i > 0 optional per-pixel weights (both default to 1; they are
// the hook for variance-aware reconstruction).
//
// The kernel is any list of pairs: the standard forward-difference grid
// (dx(x,y) = I(x+1,y) - I(x,y), dy(x,y) = I(x,y+1) - I(x,y), no rows past the last
// column / row) is one instance; the structure-adaptive kernels of Manzi 2014 Sec. 3.5
// are others. Their symmetric-neighbour rule ("add I_i - I_j = 2 Delta^i_ij and
// I_j - I_i = 2 Delta^j_ij as two rows") only needs duplicate / reversed pairs, which
// are allowed here. Pixel indices are row-major: index = y * width + x.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace dp::reconstruct {

// Default screening weight alpha (ALGORITHMS.md, Lehtinen 2013: 0.2; use 0.3-0.4 to keep
// sub-pixel geometric detail from the primal).
constexpr float kDefaultAlpha = 0.2f;

// One row of H: (H I)_r = I[j] - I[i].
struct PixelPair {
  int32_t i = 0;
  int32_t j = 0;
};

// An immutable list of pixel pairs over a width x height image.
class Kernel {
 public:
  Kernel() = default;
  // Arbitrary pairs. Throws dp::ValueError for out-of-range indices or i == j.
  Kernel(int width, int height, std::vector<PixelPair> pairs);
  // The standard forward-difference grid: first every dx row (x < width-1, row-major),
  // then every dy row (y < height-1, row-major). Enables the DCT direct solve.
  static Kernel forward_differences(int width, int height);

  int width() const { return m_width; }
  int height() const { return m_height; }
  size_t pixels() const { return size_t(m_width) * size_t(m_height); }
  size_t rows() const { return m_pairs.size(); }
  const std::vector<PixelPair>& pairs() const { return m_pairs; }
  // True only for kernels made by forward_differences().
  bool is_forward_difference_grid() const { return m_grid; }

  // Row indices of the grid kernel (valid for x < width-1, resp. y < height-1).
  size_t grid_dx_row(int x, int y) const { return size_t(y) * size_t(m_width - 1) + size_t(x); }
  size_t grid_dy_row(int x, int y) const {
    return size_t(m_height) * size_t(m_width - 1) + size_t(y) * size_t(m_width) + size_t(x);
  }

 private:
  int m_width = 0, m_height = 0;
  std::vector<PixelPair> m_pairs;
  bool m_grid = false;
};

struct Problem {
  core::Image primal;               // I_g, linear RGB
  Kernel kernel;                    // rows of H
  std::vector<Rgb> b;               // one RGB difference per kernel row
  float alpha = kDefaultAlpha;      // screening weight, > 0
  std::vector<float> row_weights;   // empty = all 1; else one finite value >= 0 per row
  std::vector<float> pixel_weights; // empty = all 1; else one finite value > 0 per pixel
};

// Throws dp::ValueError if sizes disagree, alpha is not a finite positive number, or a
// weight is out of range. NaN/Inf in primal or b are not errors (see solve.h).
void validate(const Problem& problem);

// Grid problem from a primal and dx/dy images of the same size (the last column of dx
// and the last row of dy are ignored: those rows do not exist). Throws dp::ValueError.
Problem make_grid_problem(core::Image primal, const core::Image& dx, const core::Image& dy,
                          float alpha = kDefaultAlpha);

// Row weights: `weight` for every row whose reversed pair (j, i) is also a row, 1 for
// the others. Manzi et al. 2014's symmetric pairs are two such rows (values 2 Delta^i_ij
// and 2 Delta^j_ji); in least squares they act as one row of weight 2, so against the
// alpha^2 screening term an adaptive kernel is screened like a standard one at alpha/sqrt2.
// weight = 0.5 restores the standard kernel's balance. Throws dp::ValueError unless
// weight is finite and >= 0.
std::vector<float> reversed_pair_weights(const Kernel& kernel, float weight);

// Exact differences (H I)_r of an image for every kernel row.
std::vector<Rgb> apply_kernel(const Kernel& kernel, const core::Image& image);

}  // namespace dp::reconstruct
