// Piecewise-constant distributions on [0,1) and [0,1)^2 (for environment maps and
// area-weighted triangle selection). pdfs are densities w.r.t. the unit interval/square.
#pragma once

#include <vector>

#include "core/math.h"

namespace dp::core {

class Distribution1D {
 public:
  Distribution1D() = default;
  // Negative or non-finite weights are treated as 0. All-zero weights give a uniform
  // distribution.
  explicit Distribution1D(const std::vector<float>& weights);
  size_t size() const { return m_func.size(); }
  float integral() const { return m_integral; }  // mean of the weights
  // Continuous sample in [0,1); `pdf` = density at the result; `index` = cell.
  float sample_continuous(float u, float& pdf, size_t& index) const;
  // Discrete sample of a cell with probability weight_i / sum.
  size_t sample_discrete(float u, float& pmf) const;
  float pmf(size_t i) const;
  float pdf(float x) const;

 private:
  std::vector<float> m_func;
  std::vector<double> m_cdf;  // size n + 1
  float m_integral = 0;
};

// Rows are the v (second) coordinate: p(u, v) = p(v) p(u | v).
class Distribution2D {
 public:
  // weights[v * width + u]
  Distribution2D(const std::vector<float>& weights, int width, int height);
  Vec2 sample(const Vec2& u, float& pdf) const;
  float pdf(const Vec2& p) const;

 private:
  std::vector<Distribution1D> m_conditional;
  Distribution1D m_marginal;
  int m_width, m_height;
};

}  // namespace dp::core
