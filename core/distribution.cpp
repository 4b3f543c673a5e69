#include "core/distribution.h"

#include <algorithm>

namespace dp::core {

Distribution1D::Distribution1D(const std::vector<float>& weights) : m_func(weights) {
  const size_t n = m_func.size();
  for (auto& f : m_func)
    if (!(f > 0.0f) || !std::isfinite(f)) f = 0.0f;
  m_cdf.assign(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) m_cdf[i + 1] = m_cdf[i] + double(m_func[i]) / double(n);
  const double total = m_cdf[n];
  m_integral = float(total);
  if (total <= 0.0) {
    for (size_t i = 0; i <= n; ++i) m_cdf[i] = double(i) / double(n);
    std::fill(m_func.begin(), m_func.end(), 1.0f);
    m_integral = 0.0f;
  } else {
    for (auto& c : m_cdf) c /= total;
  }
}

float Distribution1D::pmf(size_t i) const { return float(m_cdf[i + 1] - m_cdf[i]); }

float Distribution1D::pdf(float x) const {
  const size_t n = m_func.size();
  const size_t i = std::min(size_t(std::max(0.0f, x) * float(n)), n - 1);
  return pmf(i) * float(n);
}

size_t Distribution1D::sample_discrete(float u, float& pmf_out) const {
  const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), double(u));
  size_t i = size_t(std::max<std::ptrdiff_t>(0, (it - m_cdf.begin()) - 1));
  i = std::min(i, m_func.size() - 1);
  while (pmf(i) == 0.0f && i > 0) --i;  // u landed on a zero-width cell boundary
  pmf_out = pmf(i);
  return i;
}

float Distribution1D::sample_continuous(float u, float& pdf_out, size_t& index) const {
  float p;
  index = sample_discrete(u, p);
  const double lo = m_cdf[index], width = m_cdf[index + 1] - lo;
  double du = width > 0 ? (double(u) - lo) / width : 0.5;
  du = std::clamp(du, 0.0, 1.0);
  pdf_out = p * float(m_func.size());
  const float x = float((double(index) + du) / double(m_func.size()));
  return std::min(x, std::nextafter(1.0f, 0.0f));
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : m_width(width), m_height(height) {
  std::vector<float> marginal(static_cast<size_t>(height));
  m_conditional.reserve(size_t(height));
  for (int v = 0; v < height; ++v) {
    std::vector<float> row(weights.begin() + std::ptrdiff_t(v) * width, weights.begin() + std::ptrdiff_t(v + 1) * width);
    m_conditional.emplace_back(row);
    marginal[size_t(v)] = m_conditional.back().integral();
  }
  m_marginal = Distribution1D(marginal);
}

Vec2 Distribution2D::sample(const Vec2& u, float& pdf_out) const {
  float pv, pu;
  size_t iv, iu;
  const float v = m_marginal.sample_continuous(u.y(), pv, iv);
  const float x = m_conditional[iv].sample_continuous(u.x(), pu, iu);
  pdf_out = pu * pv;
  return Vec2(x, v);
}

float Distribution2D::pdf(const Vec2& p) const {
  const int iv = std::clamp(int(p.y() * float(m_height)), 0, m_height - 1);
  return m_marginal.pdf(p.y()) * m_conditional[size_t(iv)].pdf(p.x());
}

}  // namespace dp::core
