#include "kernels_adaptive/pair_kernel.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace dp::kernels_adaptive {

PairKernel standard_kernel(int width, int height) {
  if (width <= 0 || height <= 0)
    throw ValueError("kernels_adaptive: standard_kernel needs a non-empty image, got " + std::to_string(width) + "x" +
                     std::to_string(height));
  PairKernel k;
  k.width = width;
  k.height = height;
  const auto index = [width](int x, int y) { return int32_t(y * width + x); };
  // Lehtinen et al. 2013 forward differences: dx(x,y) = I(x+1,y) - I(x,y), then dy.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x + 1 < width; ++x) k.rows.push_back({index(x, y), index(x + 1, y)});
  const int32_t dy0 = int32_t(k.rows.size());
  for (int y = 0; y + 1 < height; ++y)
    for (int x = 0; x < width; ++x) k.rows.push_back({index(x, y), index(x, y + 1)});
  const auto dx_row = [&](int x, int y) { return int32_t(y * (width - 1) + x); };
  const auto dy_row = [&](int x, int y) { return dy0 + int32_t(y * width + x); };

  k.offsets.reserve(size_t(width) * size_t(height) + 1);
  k.offsets.push_back(0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Ascending neighbour index: up, left, right, down. Rows ending at this pixel
      // (b == i, value I_i - I_j) get +1, rows starting here (a == i) get -1.
      if (y > 0) k.entries.push_back({index(x, y - 1), dy_row(x, y - 1), +1.0f});
      if (x > 0) k.entries.push_back({index(x - 1, y), dx_row(x - 1, y), +1.0f});
      if (x + 1 < width) k.entries.push_back({index(x + 1, y), dx_row(x, y), -1.0f});
      if (y + 1 < height) k.entries.push_back({index(x, y + 1), dy_row(x, y), -1.0f});
      k.offsets.push_back(int32_t(k.entries.size()));
    }
  return k;
}

PairKernel adaptive_kernel(const Features& features, const AffinityParams& params) {
  validate(features);
  validate(params);
  const int32_t n = int32_t(features.pixels());
  PairKernel k;
  k.width = features.width;
  k.height = features.height;

  // P: chosen[i] = the n most similar pixels of i (sorted by index for lookups), and the
  // row of each ij in P: {a = j, b = i}, i.e. I_i - I_j (Manzi et al. 2014, Sec. 3.5).
  std::vector<int32_t> chosen_begin(size_t(n) + 1, 0), chosen, chosen_row;
  const size_t max_pairs = size_t(n) * size_t(params.neighbours);
  chosen.reserve(max_pairs);
  chosen_row.reserve(max_pairs);
  k.rows.reserve(max_pairs);
  for (int32_t i = 0; i < n; ++i) {
    std::vector<int32_t> js = most_similar(features, i, params);
    std::sort(js.begin(), js.end());
    for (int32_t j : js) {
      chosen.push_back(j);
      chosen_row.push_back(int32_t(k.rows.size()));
      k.rows.push_back({j, i});
    }
    chosen_begin[size_t(i) + 1] = int32_t(chosen.size());
  }
  // Row of ij if ij in P, else -1.
  const auto row_of = [&](int32_t i, int32_t j) -> int32_t {
    const auto b = chosen.begin() + chosen_begin[size_t(i)], e = chosen.begin() + chosen_begin[size_t(i) + 1];
    const auto it = std::lower_bound(b, e, j);
    return (it != e && *it == j) ? chosen_row[size_t(it - chosen.begin())] : -1;
  };
  // chosen_by: {k : ki in P} for every i, ascending k, in CSR form (counting sort).
  std::vector<int32_t> by_begin(size_t(n) + 1, 0), chosen_by(chosen.size());
  for (int32_t j : chosen) ++by_begin[size_t(j) + 1];
  for (size_t i = 0; i < size_t(n); ++i) by_begin[i + 1] += by_begin[i];
  {
    std::vector<int32_t> fill(by_begin.begin(), by_begin.end() - 1);
    for (int32_t i = 0; i < n; ++i)
      for (int32_t c = chosen_begin[size_t(i)]; c < chosen_begin[size_t(i) + 1]; ++c)
        chosen_by[size_t(fill[size_t(chosen[size_t(c)])]++)] = i;
  }

  // N_i = {j : ij in P or ji in P} (Sec. 4), with the row pixel i writes and its sign.
  k.offsets.reserve(size_t(n) + 1);
  k.offsets.assign(1, 0);
  k.entries.reserve(2 * max_pairs);
  std::vector<int32_t> ns;
  for (int32_t i = 0; i < n; ++i) {
    ns.assign(chosen.begin() + chosen_begin[size_t(i)], chosen.begin() + chosen_begin[size_t(i) + 1]);
    ns.insert(ns.end(), chosen_by.begin() + by_begin[size_t(i)], chosen_by.begin() + by_begin[size_t(i) + 1]);
    std::sort(ns.begin(), ns.end());
    ns.erase(std::unique(ns.begin(), ns.end()), ns.end());
    for (int32_t j : ns) {
      const int32_t own = row_of(i, j), other = row_of(j, i);
      if (own >= 0 && other >= 0)
        k.entries.push_back({j, own, +2.0f});  // symmetric: I_i - I_j = 2 Delta^i_ij
      else if (own >= 0)
        k.entries.push_back({j, own, +1.0f});  // only ij in P: I_i - I_j = Delta_ij
      else
        k.entries.push_back({j, other, -1.0f});  // only ji in P: I_j - I_i = Delta_ji
    }
    k.offsets.push_back(int32_t(k.entries.size()));
  }
  return k;
}

}  // namespace dp::kernels_adaptive
