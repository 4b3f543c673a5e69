#include "scene/bsdf/fresnel.h"

#include <complex>

namespace dp::scene {

DielectricFresnel fresnel_dielectric(float cos_i, float eta) {
  DielectricFresnel out;
  const bool outside = cos_i >= 0.0f;
  out.eta_ti = outside ? eta : 1.0f / eta;
  if (eta == 1.0f) {
    out.reflectance = 0.0f;
    out.cos_t = -cos_i;
    return out;
  }
  // Snell's law: sin_t = sin_i / eta_ti (double for accuracy near grazing angles).
  const double ci = std::min(1.0, std::abs(double(cos_i)));
  const double n = double(out.eta_ti);
  const double sin_t2 = (1.0 - ci * ci) / (n * n);
  if (sin_t2 >= 1.0) {  // total internal reflection
    out.reflectance = 1.0f;
    out.cos_t = 0.0f;
    return out;
  }
  const double ct = std::sqrt(1.0 - sin_t2);
  // Amplitude coefficients for s and p polarization (Born & Wolf 1.5.3, Eq. 21a).
  const double rs = (ci - n * ct) / (ci + n * ct);
  const double rp = (n * ci - ct) / (n * ci + ct);
  out.reflectance = float(0.5 * (rs * rs + rp * rp));
  out.cos_t = float(outside ? -ct : ct);
  return out;
}

Rgb fresnel_conductor(float cos_i, const Rgb& eta, const Rgb& k) {
  using C = std::complex<double>;
  const double ci = std::min(1.0, std::abs(double(cos_i)));
  const double si2 = 1.0 - ci * ci;
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const C n{double(eta[c]), double(k[c])};  // braces: with parentheses clang reads a function declaration
    const C n2 = n * n;
    // n cos_t = sqrt(n^2 - sin_i^2) (Snell with a complex index).
    const C n_cos_t = std::sqrt(n2 - si2);
    // |rs|^2 and |rp|^2 as ratios of squared moduli, |a / b|^2 = |a|^2 / |b|^2: the same
    // quantities without a complex division (libgcc's __divdc3, with its scaling and
    // NaN recovery, cost more than the rest of this function).
    const double rs2 = std::norm(ci - n_cos_t) / std::norm(ci + n_cos_t);
    const double rp2 = std::norm(n2 * ci - n_cos_t) / std::norm(n2 * ci + n_cos_t);
    out[c] = float(0.5 * (rs2 + rp2));
  }
  return out;
}

float fresnel_schlick(float cos_i, float f0) {
  const float m = std::clamp(1.0f - std::abs(cos_i), 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * m2 * m2 * m;
}

Rgb fresnel_schlick(float cos_i, const Rgb& f0) {
  const float m = std::clamp(1.0f - std::abs(cos_i), 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}

namespace {
// 2 \int_{t0}^{t1} F(cos t) cos t sin t dt with composite Gauss-Legendre (5 nodes).
double integrate_fdr(double t0, double t1, float eta, int panels) {
  static constexpr double kX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                   0.9061798459386640};
  static constexpr double kW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                   0.2369268850561891};
  double sum = 0;
  const double h = (t1 - t0) / panels;
  for (int p = 0; p < panels; ++p) {
    const double mid = t0 + (p + 0.5) * h;
    for (int j = 0; j < 5; ++j) {
      const double t = mid + 0.5 * h * kX[j];
      const double f = double(fresnel_dielectric(float(std::cos(t)), eta).reflectance);
      sum += kW[j] * 0.5 * h * f * std::cos(t) * std::sin(t);
    }
  }
  return 2.0 * sum;
}
}  // namespace

float fresnel_diffuse_reflectance(float eta) {
  const double half_pi = 0.5 * kPiD;
  if (eta >= 1.0f) return float(integrate_fdr(0.0, half_pi, eta, 64));
  // eta < 1: total internal reflection beyond the critical angle asin(eta).
  const double tc = std::asin(double(eta));
  return float(integrate_fdr(0.0, tc, eta, 64) + integrate_fdr(tc, half_pi, eta, 16));
}

}  // namespace dp::scene
