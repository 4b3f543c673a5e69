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

#include "core/math.h"
#include "scene/bsdfs.h"

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

}  // namespace dp::scene
