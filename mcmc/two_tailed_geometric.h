// The clamped two-tailed geometric distribution on the integers lo .. hi,
//   P(i) = base^(-|i - centre|) / Z,   Z = sum_{j=lo..hi} base^(-|j - centre|),
// with which Mitsuba's bidirectional mutation proposes path and deletion lengths
// (docs/memlt_plan.md, Sec. 2.1: base 2, centred on the current length and on 2).
// Tabulated (ranges are path lengths: tens of entries), sampled by inverse CDF, exact
// to double round-off; an empty range (lo > hi) has no mass and never samples.
#pragma once

#include <vector>

namespace dp::mcmc {

class TwoTailedGeometric {
 public:
  TwoTailedGeometric(double base, int centre, int lo, int hi);
  bool empty() const { return m_cdf.empty(); }
  int lo() const { return m_lo; }
  int hi() const { return m_lo + int(m_cdf.size()) - 1; }
  // P(i); 0 outside lo .. hi.
  double pmf(int i) const;
  // The i with CDF(i-1) <= u < CDF(i), u in [0, 1); requires !empty().
  int sample(double u) const;

 private:
  int m_lo = 0;
  std::vector<double> m_pmf;  // P(lo), ..., P(hi)
  std::vector<double> m_cdf;  // CDF(lo), ..., CDF(hi) = 1
};

}  // namespace dp::mcmc
