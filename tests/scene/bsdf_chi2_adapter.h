// Adapter from a BSDF at a fixed incident direction to the chi-square harness.
// The harness bins (cos theta, phi) uniformly and integrates each cell with a fixed
// midpoint sub-grid, which cannot resolve (a) glossy lobes much narrower than a
// sub-cell (alpha = 0.05 at normal incidence: 1 - cos theta ~ 1e-3; at grazing
// incidence the reflected lobe is only ~2 alpha cos(theta_i) wide across the plane of
// incidence) or (b) jump discontinuities of the pdf that cut through cells (the
// horizon z = 0; for GGX refraction the pdf jumps where the half vector reaches the
// horizon, on the circle wo.z = -wi.z / eta, because D_GGX(h.z = 0) = alpha^2 / pi > 0:
// relative to the peak 1 / (pi alpha^2) the jump is alpha^4).
// A chi-square test is equally valid after any fixed bijection of the sphere (with
// the density multiplied by its Jacobian), so directions are warped first:
//  * Mode `equator` (default): rotate so that the plane of incidence becomes the
//    harness equator and the normal points to +y (every lobe centre lies on the
//    equator, the horizon on the cell boundaries phi = 0, pi), then stretch
//    z'' = sign(z') sqrt|z'| across the equator (Jacobian 2 |z''|).
//  * Mode `knots` (GGX refraction with a non-negligible jump): keep the normal as the
//    harness axis, map the knots z = -1, 0, 1 and the jump circle onto cell boundaries,
//    and stretch each interval between knots, and each half of the azimuth
//    psi = phi - phi(wi) in [0, pi], [pi, 2 pi] (lobe centres at psi = 0, pi), near its
//    ends by s(t) = (1 + sign(u)(1 - sqrt(1 - |u|))) / 2, u = 2t - 1.
// Delta samples and failed samples return nullopt (absorbed).
#pragma once

#include <vector>

#include "scene/bsdf/bsdf.h"
#include "tests/support/chi2.h"

namespace dp::test {

// Piecewise warp of [k_0, k_n] onto [K_0, K_n] with end-stretched pieces.
class KnotWarp {
 public:
  KnotWarp(std::vector<double> in, std::vector<double> out) : m_in(std::move(in)), m_out(std::move(out)) {}
  double forward(double x) const {
    const size_t j = piece(m_in, x);
    const double t = std::clamp((x - m_in[j]) / (m_in[j + 1] - m_in[j]), 0.0, 1.0);
    const double u = 2 * t - 1;
    const double v = std::copysign(1.0 - std::sqrt(1.0 - std::abs(u)), u);
    return m_out[j] + 0.5 * (v + 1) * (m_out[j + 1] - m_out[j]);
  }
  // Returns x and sets dx/dy.
  double inverse(double y, double& jac) const {
    const size_t j = piece(m_out, y);
    const double s = std::clamp((y - m_out[j]) / (m_out[j + 1] - m_out[j]), 0.0, 1.0);
    const double v = 2 * s - 1;
    const double u = std::copysign(1.0 - sqr(1.0 - std::abs(v)), v);
    jac = (m_in[j + 1] - m_in[j]) / (m_out[j + 1] - m_out[j]) * 2.0 * (1.0 - std::abs(v));
    return m_in[j] + 0.5 * (u + 1) * (m_in[j + 1] - m_in[j]);
  }

 private:
  static size_t piece(const std::vector<double>& k, double x) {
    size_t j = 0;
    while (j + 2 < k.size() && x >= k[j + 1]) ++j;
    return j;
  }
  std::vector<double> m_in, m_out;
};

// The direction warps described above, for an incident direction wi.
class DirectionWarp {
 public:
  // Equator mode.
  explicit DirectionWarp(const Vec3& wi) : DirectionWarp(wi, 0.0f, false) {}
  // Knots mode if `knots`: `eta_t` = eta_o / eta_i for wi's side puts a knot on the
  // jump circle wo.z = -wi.z / eta_t. Requires theta_bins = 20 (knots on multiples of
  // 0.1) and an even phi_bins.
  DirectionWarp(const Vec3& wi, float eta_t, bool knots)
      : m_knots(knots),
        m_z(knots ? z_knots(wi, eta_t) : KnotWarp({-1.0, 1.0}, {-1.0, 1.0})),
        m_p({0.0, kPiD, 2 * kPiD}, {0.0, kPiD, 2 * kPiD}),
        m_phi0(std::atan2(double(wi.y()), double(wi.x()))) {
    const Mat3 rz = Eigen::AngleAxisf(float(-m_phi0), Vec3::UnitZ()).toRotationMatrix();
    Mat3 r;
    r << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // (x, y, z) -> (x, z, -y)
    m_rot = r * rz;
  }

  Vec3 forward(const Vec3& w) const {
    if (!m_knots) {
      const Vec3 v = m_rot * w;
      return with_z(v, std::copysign(std::sqrt(std::abs(double(v.z()))), double(v.z())));
    }
    const double z = std::clamp(double(w.z()), -1.0, 1.0);
    double psi = std::atan2(double(w.y()), double(w.x())) - m_phi0;
    psi = std::fmod(psi + 4 * kPiD, 2 * kPiD);
    const double z2 = m_z.forward(z), p2 = m_p.forward(psi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z2 * z2));
    return Vec3(float(r * std::cos(p2)), float(r * std::sin(p2)), float(z2));
  }
  // Inverse map; `jac` = |dz/dz''| |dphi/dphi''|.
  Vec3 inverse(const Vec3& v, double& jac) const {
    if (!m_knots) {
      const double z2 = double(v.z());
      jac = 2.0 * std::abs(z2);
      return m_rot.transpose() * with_z(v, std::copysign(z2 * z2, z2));
    }
    double jz = 0, jp = 0;
    const double z = m_z.inverse(std::clamp(double(v.z()), -1.0, 1.0), jz);
    double p2 = std::atan2(double(v.y()), double(v.x()));
    if (p2 < 0) p2 += 2 * kPiD;
    const double phi = m_p.inverse(p2, jp) + m_phi0;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    jac = jz * jp;
    return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }

 private:
  // Same azimuth as v, new z.
  static Vec3 with_z(const Vec3& v, double z) {
    const double r_old = std::sqrt(sqr(double(v.x())) + sqr(double(v.y())));
    const double r_new = std::sqrt(std::max(0.0, 1.0 - z * z));
    if (r_old == 0.0) return Vec3(float(r_new), 0.0f, float(z));
    return Vec3(float(double(v.x()) * r_new / r_old), float(double(v.y()) * r_new / r_old), float(z));
  }
  static KnotWarp z_knots(const Vec3& wi, float eta_t) {
    std::vector<double> zin{-1.0, 0.0, 1.0}, zout{-1.0, 0.0, 1.0};
    if (eta_t > 0.0f) {
      const double c = -double(wi.z()) / double(eta_t);
      if (std::abs(c) > 1e-3 && std::abs(c) < 1.0 - 1e-3) {
        // Nearest cell boundary (multiples of 0.1) strictly inside the half interval.
        const double b = std::copysign(std::clamp(std::round(std::abs(c) * 10.0) / 10.0, 0.1, 0.9), c);
        const long at = c < 0 ? 1 : 2;
        zin.insert(zin.begin() + at, c);
        zout.insert(zout.begin() + at, b);
      }
    }
    return KnotWarp(zin, zout);
  }
  bool m_knots;
  KnotWarp m_z, m_p;
  double m_phi0;
  Mat3 m_rot;
};

struct BsdfChi2Setup {
  DirectionSampler sampler;
  DirectionPdf pdf;
};

// `ggx_refraction_eta` > 0 (GGX rough dielectric: eta_o / eta_i for wi's side) and
// `alpha`: the knots mode is used when the relative jump alpha^4 of the refraction pdf
// exceeds 1e-3 (the harness quadrature error from a jump is proportional to it).
inline BsdfChi2Setup bsdf_chi2_setup(const scene::Bsdf& bsdf, const scene::BsdfContext& ctx, const Vec3& wi,
                                     float ggx_refraction_eta = 0.0f, float alpha = 0.0f) {
  const bool knots = ggx_refraction_eta > 0.0f && sqr(sqr(alpha)) > 1e-3f;
  const DirectionWarp warp(wi, ggx_refraction_eta, knots);
  BsdfChi2Setup s;
  s.sampler = [&bsdf, ctx, wi, warp](core::Rng& rng) -> std::optional<Vec3> {
    const float ul = rng.uniform();
    const auto bs = bsdf.sample(ctx, wi, ul, rng.uniform2());
    if (!bs || bs->is_delta()) return std::nullopt;
    return warp.forward(bs->wo);
  };
  s.pdf = [&bsdf, ctx, wi, warp](const Vec3& v) {
    double jac = 0;
    const Vec3 wo = warp.inverse(v, jac);
    return double(bsdf.pdf(ctx, wi, wo)) * jac;
  };
  return s;
}

inline Chi2Options bsdf_chi2_options(int test_count, uint64_t seed) {
  Chi2Options o;
  o.theta_bins = 20;
  o.phi_bins = 40;
  o.samples = 200000;
  o.significance = 0.01;
  o.test_count = test_count;
  o.seed = seed;
  return o;
}

}  // namespace dp::test
