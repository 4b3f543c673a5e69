// Welch t-tests between two sets of independent runs (fixed seeds): the run-to-run spread
// gives each estimator's standard error whatever its internal correlation (MCMC chains),
// so thresholds come from the estimators' variances, not from tuning.
#pragma once

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace dp::test {

struct Moments {
  double mean = 0, var = 0;  // sample mean and unbiased sample variance of the runs
  size_t n = 0;
};

inline Moments moments(const std::vector<double>& v, double scale = 1.0) {
  Moments m;
  m.n = v.size();
  for (double x : v) m.mean += scale * x;
  m.mean /= double(v.size());
  for (double x : v) m.var += (scale * x - m.mean) * (scale * x - m.mean);
  m.var /= double(v.size() - 1);
  return m;
}

// |t| / (two-sided critical value at level alpha) of Welch's test of equal means: > 1 rejects.
inline double welch_ratio(const Moments& a, const Moments& b, double alpha) {
  const double va = a.var / double(a.n), vb = b.var / double(b.n);
  if (!(va + vb > 0)) return a.mean == b.mean ? 0.0 : std::numeric_limits<double>::infinity();
  const double t = (a.mean - b.mean) / std::sqrt(va + vb);
  // Welch-Satterthwaite degrees of freedom.
  const double dof = (va + vb) * (va + vb) / (va * va / double(a.n - 1) + vb * vb / double(b.n - 1));
  return std::abs(t) / boost::math::quantile(boost::math::complement(boost::math::students_t(dof), alpha / 2));
}

// Statistic 0 tested at `alpha`, statistics 1.. at the Sidak level of a family of them
// (family-wise `alpha`); returns the largest |t|/crit and the first one in `first`.
inline double worst_welch(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                          double alpha, double* first = nullptr) {
  const double r0 = welch_ratio(moments(a[0]), moments(b[0]), alpha);
  if (first) *first = r0;
  const double sidak = 1.0 - std::pow(1.0 - alpha, 1.0 / double(a.size() - 1));
  double worst = r0;
  for (size_t i = 1; i < a.size(); ++i) worst = std::max(worst, welch_ratio(moments(a[i]), moments(b[i]), sidak));
  return worst;
}

// Every statistic at the Sidak level of the family (family-wise `alpha`); the largest |t|/crit.
inline double sidak_welch(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                          double alpha) {
  const double sidak = 1.0 - std::pow(1.0 - alpha, 1.0 / double(a.size()));
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, welch_ratio(moments(a[i]), moments(b[i]), sidak));
  return worst;
}

}  // namespace dp::test
