#include "scene/bsdf/microfacet.h"

#include <boost/math/special_functions/erf.hpp>

#include "core/error.h"

namespace dp::scene {

Microfacet::Microfacet(MicrofacetType type, float alpha_u, float alpha_v)
    : m_type(type), m_alpha_u(alpha_u), m_alpha_v(alpha_v) {
  DP_CHECK(alpha_u > 0.0f && alpha_v > 0.0f, "microfacet alpha must be positive");
  // Very small alphas overflow D in float; clamp like a numerically smooth limit.
  m_alpha_u = std::max(m_alpha_u, 1e-4f);
  m_alpha_v = std::max(m_alpha_v, 1e-4f);
}

Vec3 Microfacet::sample_visible(const Vec3& wi, const Vec2& u) const {
  return m_type == MicrofacetType::ggx ? sample_visible_ggx(wi, u) : sample_visible_beckmann(wi, u);
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", Listing 1: the
// visible GGX normals of a stretched (alpha = 1) configuration are the visible
// hemisphere's projected disk, warped so that the disk half behind wi shrinks.
Vec3 Microfacet::sample_visible_ggx(const Vec3& wi, const Vec2& u) const {
  const Vec3 vh = Vec3(m_alpha_u * wi.x(), m_alpha_v * wi.y(), wi.z()).normalized();
  const float len2 = vh.x() * vh.x() + vh.y() * vh.y();
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y(), vh.x(), 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = vh.cross(t1);
  const float r = std::sqrt(u.x());
  const float phi = 2.0f * kPi * u.y();
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z());
  p2 = (1.0f - s) * safe_sqrt(1.0f - p1 * p1) + s * p2;  // Heitz 2018, Eq. (Sec. 4.2, "warp")
  const Vec3 nh = p1 * t1 + p2 * t2 + safe_sqrt(1.0f - p1 * p1 - p2 * p2) * vh;
  // Unstretch (the normal transforms with the inverse transpose of the stretch).
  return Vec3(m_alpha_u * nh.x(), m_alpha_v * nh.y(), std::max(1e-7f, nh.z())).normalized();
}

namespace {
// erf^-1 evaluated in double. Boost's default policy promotes double arguments to long
// double (x87), several times slower; the double-precision rational approximations are
// accurate to a few double ulps, far below the float normals built from them.
using DoublePolicy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
double erf_inv_double(double x) { return boost::math::erf_inv(x, DoublePolicy()); }

// Visible slopes of the alpha = 1 Beckmann distribution seen from an incident direction
// with cot(theta) = a, in the frame where the incident azimuth is 0. Slope x has the
// density p(x) ~ max(0, a - x) exp(-x^2) (projected-area weighting of the slope
// distribution exp(-x^2-y^2)/pi, Heitz & d'Eon 2014, Eq. 7), slope y ~ N(0, 1/2)
// independently. The CDF of x, C(x) = a sqrt(pi)/2 erfc(-x) + exp(-x^2)/2 (up to
// normalization), is inverted by Newton's method kept inside a bisection bracket.
double sample_beckmann_slope_x(double a, double u) {
  const double sqrt_pi = std::sqrt(kPiD);
  const auto cdf = [&](double x) { return 0.5 * a * sqrt_pi * std::erfc(-x) + 0.5 * std::exp(-x * x); };
  // Beyond |x| = 6 the density is below exp(-36) of its peak: the bracket is exact in
  // float precision.
  double hi = std::min(a, 6.0), lo = -6.0;
  const double target = u * cdf(hi);
  double x = std::clamp(a > 1.0 ? erf_inv_double(std::clamp(2.0 * u - 1.0, -0.999999, 0.999999)) : 0.0, lo, hi);
  for (int it = 0; it < 60; ++it) {
    const double f = cdf(x) - target;
    if (f > 0) hi = x; else lo = x;
    if (hi - lo < 1e-9) break;
    const double df = (a - x) * std::exp(-x * x);
    double next = df > 0 ? x - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) < 1e-10) { x = next; break; }
    x = next;
  }
  return x;
}
}  // namespace

Vec3 Microfacet::sample_visible_beckmann(const Vec3& wi, const Vec2& u) const {
  // 1. Stretch to the alpha = 1 configuration (Heitz & d'Eon 2014, Sec. 4, step 1).
  const Vec3 ws = Vec3(m_alpha_u * wi.x(), m_alpha_v * wi.y(), wi.z()).normalized();
  const double sin_t = std::sqrt(sqr(double(ws.x())) + sqr(double(ws.y())));
  double cos_phi = 1.0, sin_phi = 0.0;
  if (sin_t > 1e-9) {
    cos_phi = double(ws.x()) / sin_t;
    sin_phi = double(ws.y()) / sin_t;
  }
  // 2. Sample visible slopes for the incident elevation (step 2).
  const double a = sin_t > 1e-12 ? double(ws.z()) / sin_t : 1e12;
  const double sx = sample_beckmann_slope_x(a, double(u.x()));
  const double sy = erf_inv_double(std::clamp(2.0 * double(u.y()) - 1.0, -1.0 + 1e-12, 1.0 - 1e-12));
  // 3. Rotate back to the incident azimuth, 4. unstretch, 5. slope -> normal.
  const double rx = cos_phi * sx - sin_phi * sy;
  const double ry = sin_phi * sx + cos_phi * sy;
  const double mx = -double(m_alpha_u) * rx, my = -double(m_alpha_v) * ry;
  const double len = std::sqrt(mx * mx + my * my + 1.0);
  return Vec3(float(mx / len), float(my / len), float(1.0 / len));
}

}  // namespace dp::scene
