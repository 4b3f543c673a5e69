#include "mcmc/bidir_choice.h"

#include <algorithm>

#include "mcmc/two_tailed_geometric.h"

namespace dp::mcmc {

namespace {

int min_deletion(int k, int k_new) { return std::max(k == k_new ? 2 : 1, k - k_new + 1); }

// Left ends admissible for deletion length kd and ka new edges (step 4), appended to out.
int admissible_left_ends(const BidirShape& shape, int kd, int ka, std::vector<int>* out) {
  int lo = 0, hi = shape.k - kd;
  if (kd == 1 || ka == 1) {
    ++lo;
    --hi;
  }
  int n = 0;
  for (int l = lo; l <= hi; ++l)
    if (!shape.degenerate[size_t(l)] && !shape.degenerate[size_t(l + kd)]) {
      ++n;
      if (out) out->push_back(l);
    }
  return n;
}

}  // namespace

void bidir_split_range(const BidirShape& shape, const BidirChoice& c, int& s_min, int& s_max) {
  s_min = c.l == 0 && !shape.light_hittable ? 1 : 0;
  s_max = c.ka - 1 - (c.m == shape.k && !shape.camera_hittable ? 1 : 0);
}

bool sample_bidir_choice(const BidirShape& shape, const BidirLengths& lengths, pathspace::SampleStream& stream,
                         BidirChoice& out) {
  const int k = shape.k;
  const float u_len = stream.next(), u_del = stream.next(), u_left = stream.next(), u_split = stream.next();
  const TwoTailedGeometric length(2.0, k, lengths.k_min, lengths.k_max);
  if (length.empty()) return false;
  const int k_new = length.sample(u_len);
  const TwoTailedGeometric deletion(2.0, 2, min_deletion(k, k_new), k);
  if (deletion.empty()) return false;
  const int kd = deletion.sample(u_del);
  const int ka = k_new - k + kd;
  std::vector<int> ends;
  const int n = admissible_left_ends(shape, kd, ka, &ends);
  if (n == 0) return false;
  out.l = ends[size_t(std::min(int(float(n) * u_left), n - 1))];
  out.m = out.l + kd;
  out.ka = ka;
  int s_min = 0, s_max = 0;
  bidir_split_range(shape, out, s_min, s_max);
  if (s_min > s_max) return false;
  out.s = std::min(s_min + int(float(s_max - s_min + 1) * u_split), s_max);
  return true;
}

double bidir_choice_pmf(const BidirShape& shape, const BidirLengths& lengths, const BidirChoice& c) {
  const int k = shape.k, kd = c.kd(), k_new = c.new_length(k);
  if (kd < 1 || c.ka < 1 || c.l < 0 || c.m > k) return 0.0;
  int s_min = 0, s_max = 0;
  bidir_split_range(shape, c, s_min, s_max);
  if (s_min > s_max) return 0.0;
  std::vector<int> ends;
  const int n = admissible_left_ends(shape, kd, c.ka, &ends);
  if (std::find(ends.begin(), ends.end(), c.l) == ends.end()) return 0.0;  // also n = 0
  const TwoTailedGeometric length(2.0, k, lengths.k_min, lengths.k_max);
  const TwoTailedGeometric deletion(2.0, 2, min_deletion(k, k_new), k);
  return length.pmf(k_new) * deletion.pmf(kd) / double(n) / double(s_max - s_min + 1);
}

}  // namespace dp::mcmc
