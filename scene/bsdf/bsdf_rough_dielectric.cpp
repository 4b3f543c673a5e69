// Rough dielectric interface (Walter et al. 2007, "Microfacet Models for Refraction
// through Rough Surfaces"), two-sided, Beckmann or GGX (isotropic alpha).
// eta = int_ior / ext_ior if wi.z > 0, else 1 / that (eta = eta_o / eta_i for
// refraction). Half vectors: reflection h = normalize(wi + wo) (Eq. 13), refraction
// h = normalize(-(wi + eta wo)) (Eq. 16), both flipped to h.z > 0.
//   f_r = F D G / (4 |cos wi| |cos wo|)                                          (Eq. 20)
//   f_t = |wi.h| |wo.h| eta^2 (1 - F) D G / (|cos wi| |cos wo| (wi.h + eta wo.h)^2) (Eq. 21)
// f_t is the physical BTDF (light flowing from wi to wo: importance mode); radiance
// mode multiplies it by 1 / eta^2 (Veach 1997, Eq. 5.19), which makes
// f_radiance(wi, wo) = f_importance(wo, wi).
// Sampling: visible normals m ~ D_wi of the flipped wi (Heitz & d'Eon 2014), reflect
// with probability F(wi.m), else refract. pdf = D_wi(h) F / (4 |wo.h|) for reflection
// (Eq. 14) and D_wi(h) (1 - F) eta^2 |wo.h| / (wi.h + eta wo.h)^2 for refraction
// (Eq. 17). Weights: G1(wo) times the specular factor (and 1 / eta^2 in radiance mode).
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"
#include "scene/bsdf/fresnel.h"
#include "scene/bsdf/microfacet.h"

namespace dp::scene {
namespace {

class RoughDielectricBsdf final : public Bsdf {
 public:
  RoughDielectricBsdf(float eta, const Microfacet& d, TexturePtr r, TexturePtr t)
      : m_eta(eta), m_distr(d), m_r(std::move(r)), m_t(std::move(t)) {}

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    Geometry g;
    if (!half_vector(wi, wo, g)) return Rgb::Zero();
    const float d = m_distr.D(g.h);
    if (d == 0.0f) return Rgb::Zero();
    const float gg = m_distr.G(wi, wo, g.h);
    if (gg == 0.0f) return Rgb::Zero();
    const float f = fresnel_dielectric(wi.dot(g.h), m_eta).reflectance;
    if (g.reflect)  // Walter 2007, Eq. 20
      return detail::eval_or(m_r, ctx.uv) * (f * d * gg / (4.0f * std::abs(wi.z() * wo.z())));
    // Walter 2007, Eq. 21 (relative eta = eta_o / eta_i).
    const float idh = wi.dot(g.h), odh = wo.dot(g.h);
    const float denom = idh + g.eta * odh;
    float v = std::abs(idh * odh) * sqr(g.eta) * (1.0f - f) * d * gg / (std::abs(wi.z() * wo.z()) * sqr(denom));
    if (ctx.mode == TransportMode::radiance) v /= sqr(g.eta);
    return detail::eval_or(m_t, ctx.uv) * v;
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    Geometry g;
    if (!half_vector(wi, wo, g)) return 0.0f;
    const Vec3 wi_up = wi.z() > 0.0f ? wi : Vec3(-wi);
    const float pm = m_distr.pdf_visible(wi_up, g.h);
    if (pm == 0.0f) return 0.0f;
    const float f = fresnel_dielectric(wi.dot(g.h), m_eta).reflectance;
    const float odh = wo.dot(g.h);
    if (odh * wo.z() <= 0.0f) return 0.0f;  // wo must see the same side of h (cf. G1)
    if (g.reflect) return pm * f / (4.0f * std::abs(odh));  // Walter 2007, Eq. 14
    const float denom = wi.dot(g.h) + g.eta * odh;
    return pm * (1.0f - f) * sqr(g.eta) * std::abs(odh) / sqr(denom);  // Walter 2007, Eq. 17
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    if (wi.z() == 0.0f) return std::nullopt;
    const Vec3 wi_up = wi.z() > 0.0f ? wi : Vec3(-wi);
    const Vec3 m = m_distr.sample_visible(wi_up, u);
    const float c = wi.dot(m);
    const DielectricFresnel fr = fresnel_dielectric(c, m_eta);
    BsdfSample s;
    if (u_lobe < fr.reflectance) {
      s.wo = (2.0f * c * m - wi).normalized();
      if (s.wo.z() * wi.z() <= 0.0f) return std::nullopt;
      s.weight = detail::eval_or(m_r, ctx.uv) * m_distr.G1(s.wo, m);
      s.lobe = kGlossyReflection;
    } else {
      s.wo = detail::refract_about(wi, m, c, fr.cos_t, fr.eta_ti).normalized();
      if (s.wo.z() * wi.z() >= 0.0f) return std::nullopt;
      float w = m_distr.G1(s.wo, m);
      if (ctx.mode == TransportMode::radiance) w /= sqr(fr.eta_ti);
      s.weight = detail::eval_or(m_t, ctx.uv) * w;
      s.eta = fr.eta_ti;
      s.lobe = kGlossyTransmission;
    }
    s.pdf = pdf(ctx, wi, s.wo);
    if (!(s.pdf > 0.0f) || is_black(s.weight)) return std::nullopt;
    return s;
  }

  float roughness() const override { return m_distr.alpha_u(); }
  uint32_t lobes() const override { return kGlossyReflection | kGlossyTransmission; }
  std::string name() const override { return "roughdielectric"; }
  Rgb albedo(const BsdfContext& ctx) const override { return detail::eval_or(m_t, ctx.uv); }
  bool has_texture() const override { return detail::varies(m_r) || detail::varies(m_t); }

 private:
  struct Geometry {
    Vec3 h;
    float eta = 1;  // eta_o / eta_i for refraction, 1 for reflection
    bool reflect = true;
  };
  bool half_vector(const Vec3& wi, const Vec3& wo, Geometry& g) const {
    if (wi.z() == 0.0f || wo.z() == 0.0f) return false;
    g.reflect = wi.z() * wo.z() > 0.0f;
    g.eta = g.reflect ? 1.0f : (wi.z() > 0.0f ? m_eta : 1.0f / m_eta);
    const Vec3 h = g.reflect ? Vec3(wi + wo) : Vec3(wi + g.eta * wo);
    const float len = h.norm();
    if (!(len > 0.0f)) return false;
    g.h = (h.z() < 0.0f ? -h : h) / len;
    return true;
  }

  float m_eta;
  Microfacet m_distr;
  TexturePtr m_r, m_t;
};

}  // namespace

BsdfPtr detail::make_rough_dielectric(float int_ior, float ext_ior, float alpha, MicrofacetType dist,
                                      TexturePtr specular_reflectance, TexturePtr specular_transmittance) {
  DP_CHECK(int_ior != ext_ior, "roughdielectric: interior and exterior ior must differ");
  return std::make_shared<RoughDielectricBsdf>(int_ior / ext_ior, Microfacet(dist, alpha),
                                               std::move(specular_reflectance), std::move(specular_transmittance));
}

}  // namespace dp::scene
