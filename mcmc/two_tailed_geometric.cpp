#include "mcmc/two_tailed_geometric.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace dp::mcmc {

TwoTailedGeometric::TwoTailedGeometric(double base, int centre, int lo, int hi) : m_lo(lo) {
  if (lo > hi) return;
  m_pmf.resize(size_t(hi - lo + 1));
  double z = 0;
  for (int i = lo; i <= hi; ++i) z += m_pmf[size_t(i - lo)] = std::pow(base, -double(std::abs(i - centre)));
  m_cdf.resize(m_pmf.size());
  double sum = 0;
  for (size_t k = 0; k < m_pmf.size(); ++k) {
    m_pmf[k] /= z;
    m_cdf[k] = sum += m_pmf[k];
  }
  m_cdf.back() = 1.0;
}

double TwoTailedGeometric::pmf(int i) const {
  if (i < m_lo || i > hi()) return 0.0;
  return m_pmf[size_t(i - m_lo)];
}

int TwoTailedGeometric::sample(double u) const {
  const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
  return m_lo + int(std::min<std::ptrdiff_t>(it - m_cdf.begin(), std::ptrdiff_t(m_cdf.size()) - 1));
}

}  // namespace dp::mcmc
