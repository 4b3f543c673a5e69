#include "scene/media/grid_tracking.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dp::scene {

namespace {

// The majorant's rate and the density that corresponds to it.
float majorant_density(const DensityGrid& g, GridTrackingFault fault) {
  if (fault != GridTrackingFault::majorant_from_mean) return g.max_value;
  return float(std::accumulate(g.values.begin(), g.values.end(), 0.0) / double(g.values.size()));
}

// Next tentative collision after t at rate mu.
float step(float t, float mu, core::Rng& rng) { return t - std::log1p(-rng.uniform()) / mu; }

}  // namespace

FreeFlightSample sample_free_flight_grid(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max,
                                         core::Rng& rng, GridTrackingFault fault) {
  FreeFlightSample s;
  s.t = t_max;
  s.scattered = false;
  s.weight = Rgb::Ones();
  s.pdf = 0.0f;
  const DensityGrid& g = *m.density;
  const float st = m.sigma_t()[0], dmax = majorant_density(g, fault), mu = st * dmax;
  float t0 = 0, t1 = 0;
  if (!(mu > 0.0f) || !g.clip(o, d, t_max, t0, t1)) return s;
  for (float t = t0;;) {
    t = step(t, mu, rng);
    if (!(t < t1)) return s;
    if (rng.uniform() * dmax < g.lookup(o + t * d)) {
      s.t = t;
      s.scattered = true;
      s.weight = m.sigma_s / st;  // Tr sigma_s / (sigma_t Tr): the albedo
      return s;
    }
  }
}

Rgb transmittance_grid(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max, core::Rng& rng,
                       GridTrackingFault fault) {
  const DensityGrid& g = *m.density;
  const float st = m.sigma_t()[0], dmax = majorant_density(g, fault), mu = st * dmax;
  float t0 = 0, t1 = 0;
  if (!(mu > 0.0f) || !g.clip(o, d, t_max, t0, t1)) return Rgb::Ones();
  float tr = 1.0f;
  for (float t = step(t0, mu, rng); t < t1 && tr > 0.0f; t = step(t, mu, rng))
    tr *= std::max(0.0f, 1.0f - g.lookup(o + t * d) / dmax);
  return Rgb::Constant(tr);
}

void TransmittanceProfile::track(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max,
                                 core::Rng& rng) {
  m_t.clear();
  m_v.clear();
  const DensityGrid& g = *m.density;
  const float st = m.sigma_t()[0], dmax = g.max_value, mu = st * dmax;
  float t0 = 0, t1 = 0;
  if (!(mu > 0.0f) || !g.clip(o, d, t_max, t0, t1)) return;
  float tr = 1.0f;
  for (float t = step(t0, mu, rng); t < t1 && tr > 0.0f; t = step(t, mu, rng)) {
    tr *= std::max(0.0f, 1.0f - g.lookup(o + t * d) / dmax);
    m_t.push_back(t);
    m_v.push_back(tr);
  }
}

float TransmittanceProfile::at(float t) const {
  const size_t k = size_t(std::lower_bound(m_t.begin(), m_t.end(), t) - m_t.begin());  // collisions before t
  return k == 0 ? 1.0f : m_v[k - 1];
}

float TransmittanceProfile::integral(float a, float b) const {
  double sum = 0.0;
  float from = a;
  size_t k = size_t(std::upper_bound(m_t.begin(), m_t.end(), a) - m_t.begin());  // first collision after a
  float v = k == 0 ? 1.0f : m_v[k - 1];
  for (; k < m_t.size() && m_t[k] < b; ++k) {
    sum += double(v) * double(m_t[k] - from);
    from = m_t[k];
    v = m_v[k];
  }
  sum += double(v) * double(b - from);
  return float(sum);
}

}  // namespace dp::scene
