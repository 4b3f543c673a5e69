// Microfacet normal distributions (Beckmann, GGX), isotropic or anisotropic.
// Contract: all vectors in the local shading frame (z = macro-surface normal).
//  * D(m): distribution of microfacet normals, normalized so that
//    \int D(m) cos(theta_m) dm = 1 (Walter et al. 2007, Eq. 4), measure: solid angle.
//  * G1(w, m): Smith masking (Heitz 2014, "Understanding the Masking-Shadowing
//    Function", Eq. 43 with the Lambda of Sec. 5.3), 0 on the back side of m.
//  * G(wi, wo, m): separable Smith shadowing-masking G1(wi) G1(wo) (Walter 2007, Eq. 23).
//  * sample_visible(wi, u) draws m from the distribution of normals visible from wi
//    (wi.z > 0 required; callers flip wi to the upper hemisphere), whose solid-angle
//    density is pdf_visible = G1(wi) max(0, wi.m) D(m) / cos(wi) (Heitz 2014, Eq. 17).
//    GGX: Heitz 2018, "Sampling the GGX Distribution of Visible Normals".
//    Beckmann: slope-space sampling after stretching (Heitz & d'Eon 2014, Sec. 4;
//    Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann
//    Distribution"), with a safeguarded Newton inversion of the slope CDF.
#pragma once

#include <cmath>

#include "core/math.h"
#include "scene/bsdf/bsdfs.h"

namespace dp::scene {

class Microfacet {
 public:
  Microfacet(MicrofacetType type, float alpha_u, float alpha_v);
  Microfacet(MicrofacetType type, float alpha) : Microfacet(type, alpha, alpha) {}

  MicrofacetType type() const { return m_type; }
  float alpha_u() const { return m_alpha_u; }
  float alpha_v() const { return m_alpha_v; }
  bool is_anisotropic() const { return m_alpha_u != m_alpha_v; }

  float D(const Vec3& m) const;
  // Smith Lambda(w): G1 = 1 / (1 + Lambda).
  float lambda(const Vec3& w) const;
  float G1(const Vec3& w, const Vec3& m) const;
  float G(const Vec3& wi, const Vec3& wo, const Vec3& m) const { return G1(wi, m) * G1(wo, m); }

  Vec3 sample_visible(const Vec3& wi, const Vec2& u) const;
  float pdf_visible(const Vec3& wi, const Vec3& m) const;

 private:
  Vec3 sample_visible_ggx(const Vec3& wi, const Vec2& u) const;
  Vec3 sample_visible_beckmann(const Vec3& wi, const Vec2& u) const;

  MicrofacetType m_type;
  float m_alpha_u, m_alpha_v;
};

// D, Lambda, G1 and pdf_visible are inline: the BSDFs' eval/pdf/sample call them several
// times per path vertex.
inline float Microfacet::D(const Vec3& m) const {
  const float cz = m.z();
  if (cz <= 0.0f) return 0.0f;
  const float cz2 = cz * cz;
  const float ax = m.x() / m_alpha_u, ay = m.y() / m_alpha_v;
  // x^2/au^2 + y^2/av^2 = tan^2(theta) * (cos^2 phi / au^2 + sin^2 phi / av^2) * cos^2 theta
  const float e = ax * ax + ay * ay;
  float d;
  if (m_type == MicrofacetType::beckmann) {
    // Walter 2007, Eq. 25 (anisotropic form: Heitz 2014, Eq. 84).
    d = std::exp(-e / cz2) / (kPi * m_alpha_u * m_alpha_v * cz2 * cz2);
  } else {
    // Walter 2007, Eq. 33 (anisotropic form: Heitz 2014, Eq. 85).
    const float t = e + cz2;
    d = 1.0f / (kPi * m_alpha_u * m_alpha_v * t * t);
  }
  return d;
}

inline float Microfacet::lambda(const Vec3& w) const {
  const float cz2 = w.z() * w.z();
  if (cz2 <= 0.0f) return kInfinity;
  // alpha_o^2 tan^2 theta (Heitz 2014, Eq. 80): projected roughness along w's azimuth.
  const float a2t2 = (sqr(w.x() * m_alpha_u) + sqr(w.y() * m_alpha_v)) / cz2;
  if (a2t2 <= 0.0f) return 0.0f;
  if (m_type == MicrofacetType::ggx) {
    // Heitz 2014, Eq. 86.
    return 0.5f * (-1.0f + std::sqrt(1.0f + a2t2));
  }
  // Heitz 2014, Eq. 83, with a = 1 / (alpha tan theta).
  const double a = 1.0 / std::sqrt(double(a2t2));
  return float(0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPiD)));
}

inline float Microfacet::G1(const Vec3& w, const Vec3& m) const {
  // Back-facing microfacets are not visible (Walter 2007, Eq. 27 chi+ term).
  if (w.dot(m) * w.z() <= 0.0f) return 0.0f;
  const float l = lambda(w);
  return std::isfinite(l) ? 1.0f / (1.0f + l) : 0.0f;
}

inline float Microfacet::pdf_visible(const Vec3& wi, const Vec3& m) const {
  const float cz = std::abs(wi.z());
  if (cz == 0.0f) return 0.0f;
  // Heitz 2014, Eq. 17 (distribution of visible normals).
  return G1(wi, m) * std::max(0.0f, wi.dot(m)) * D(m) / cz;
}

}  // namespace dp::scene
