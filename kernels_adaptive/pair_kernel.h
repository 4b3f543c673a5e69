// Pixel-pair kernels for gradient-domain MLT (Manzi et al. 2014, Sec. 3.5, Sec. 4,
// Algorithm 1): which constraint rows exist, and where a sampled gradient goes.
//
// Pair set P (adaptive_kernel): ij in P iff j is one of the n most similar pixels of i
// (affinity.h). For every ij in P there is exactly one row, {a = j, b = i}, i.e. the
// constraint  I_i - I_j = value. Then
//   * symmetric pair (ij in P and ji in P): two rows, {j -> i} owned by i and
//     {i -> j} owned by j; pixel i writes  I_i - I_j = 2 Delta^i_ij  (Sec. 3.5,
//     "Symmetric Neighbors"; Algorithm 1 line 23);
//   * non-symmetric pair (only ij in P): one row {j -> i}, I_i - I_j = Delta_ij, written
//     by both pixels: Delta^i_ij by i and Delta^j_ij = -Delta^j_ji by j (Sec. 3.5,
//     "Non-Symmetric Neighbors"; Algorithm 1 lines 15-20).
// N_i = {k : ik in P or ki in P} (Sec. 4, extended path space Omega'_i = Omega_i x N_i).
//
// Entry (i -> j, row r, weight w): a sample s of Delta^i_ij (pixel i's part of I_i - I_j,
// Eq. 4) is added to row r as  w * |N_i| * s  (Algorithm 1 line 13 multiplies by |N_i|
// because the neighbour j is drawn uniformly from N_i). w = +2 for a symmetric pair,
// +1 if the row is {a = j, b = i} (value I_i - I_j), -1 if it is {a = i, b = j}.
// Entries of a pixel are sorted by j.
//
// standard_kernel: the 4-neighbour forward differences of Lehtinen et al. 2013, rows in
// reconstruct::Kernel::forward_differences order (all dx rows, then all dy rows); each
// row is written by both of its pixels (w = -1 for the left/top pixel, +1 for the other).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "kernels_adaptive/affinity.h"
#include "kernels_adaptive/features.h"
#include "reconstruct/problem.h"

namespace dp::kernels_adaptive {

struct PairKernel {
  int width = 0, height = 0;
  // Constraint rows: row r says  I[b] - I[a] = value   (a, b pixel indices y*W+x)
  std::vector<reconstruct::PixelPair> rows;  // reconstruct::PixelPair{i = a, j = b}
  // N_i for every pixel i: entries[offsets[i] .. offsets[i+1]) (offsets has W*H+1 values).
  struct Entry {
    int32_t j;
    int32_t row;
    float weight;
  };
  std::vector<int32_t> offsets;
  std::vector<Entry> entries;
};

// 4-neighbour forward differences (rows identical in order to
// reconstruct::Kernel::forward_differences). Throws dp::ValueError unless width, height > 0.
PairKernel standard_kernel(int width, int height);

// Structure-adaptive kernel from feature buffers (Manzi et al. 2014, Sec. 3.5). Rows are
// ordered by owning pixel i (row-major), then by j. Throws dp::ValueError for invalid
// features or parameters.
PairKernel adaptive_kernel(const Features& features, const AffinityParams& params = {});

// N_i with rows and weights (|N_i| = its size).
inline std::span<const PairKernel::Entry> neighbours(const PairKernel& k, int32_t i) {
  return {k.entries.data() + k.offsets[size_t(i)], size_t(k.offsets[size_t(i) + 1] - k.offsets[size_t(i)])};
}

}  // namespace dp::kernels_adaptive
