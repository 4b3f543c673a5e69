#include "scene/bsdf/rough_transmittance.h"

#include "core/error.h"
#include "scene/bsdf/fresnel.h"

namespace dp::scene {

float RoughTransmittance::compute(const Microfacet& distr, float eta, float mu, int strata) {
  mu = std::clamp(mu, 1e-4f, 1.0f);
  const Vec3 wi(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  double sum = 0;
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b) {
      const Vec2 u((float(a) + 0.5f) / float(strata), (float(b) + 0.5f) / float(strata));
      const Vec3 m = distr.sample_visible(wi, u);
      const float c = wi.dot(m);
      if (c <= 0.0f) continue;
      const DielectricFresnel fr = fresnel_dielectric(c, eta);
      if (fr.cos_t == 0.0f) continue;  // total internal reflection
      // Refraction about m (Walter 2007, Eq. 40); cos_t < 0 on the far side.
      const Vec3 wt = (fr.cos_t + c / fr.eta_ti) * m - wi / fr.eta_ti;
      sum += double((1.0f - fr.reflectance) * distr.G1(wt, m));
    }
  return float(sum / (double(strata) * strata));
}

RoughTransmittance::RoughTransmittance(MicrofacetType type, float alpha, float eta, int nodes, int strata) {
  DP_CHECK(nodes >= 2 && strata >= 1, "bad rough transmittance resolution");
  const Microfacet distr(type, alpha);
  m_table.resize(size_t(nodes));
  for (int j = 0; j < nodes; ++j) m_table[size_t(j)] = compute(distr, eta, float(j) / float(nodes - 1), strata);
  // 2 \int_0^1 T(mu) mu dmu by the trapezoidal rule on the (piecewise linear) table,
  // exact for the interpolant that eval() uses.
  double sum = 0;
  const double h = 1.0 / (nodes - 1);
  for (int j = 0; j + 1 < nodes; ++j) {
    const double m0 = j * h, m1 = (j + 1) * h;
    const double t0 = double(m_table[size_t(j)]), t1 = double(m_table[size_t(j + 1)]);
    // \int_{m0}^{m1} (t0 + (t1 - t0)(mu - m0)/h) mu dmu
    sum += t0 * (m1 * m1 - m0 * m0) / 2 + (t1 - t0) / h * ((m1 * m1 * m1 - m0 * m0 * m0) / 3 - m0 * (m1 * m1 - m0 * m0) / 2);
  }
  m_diffuse = float(2.0 * sum);
}

float RoughTransmittance::eval(float mu) const {
  const float x = std::clamp(mu, 0.0f, 1.0f) * float(m_table.size() - 1);
  const size_t i = std::min(size_t(x), m_table.size() - 2);
  const float t = x - float(i);
  return (1.0f - t) * m_table[i] + t * m_table[i + 1];
}

}  // namespace dp::scene
