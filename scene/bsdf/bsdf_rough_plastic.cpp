// Rough plastic: a diffuse base under a rough dielectric coating, following the
// semantics of Mitsuba 0.6 "roughplastic" (Beckmann or GGX, isotropic). One-sided.
//  * Specular: Walter et al. 2007, Eq. 20, f_s = F(wi.h) D G / (4 cos wi cos wo) * ks.
//  * Diffuse (internal scattering, Weidlich & Wilkie 2007 style):
//      f_d = rho' / pi * T(cos wi) T(cos wo) / eta^2,
//    T(mu) = energy transmitted through the rough interface from outside
//    (rough_transmittance.h), rho' = rho / (1 - Fdr) or, with nonlinear,
//    rho / (1 - rho Fdr), where Fdr = 1 - (diffuse transmittance of the interface
//    seen from inside, eta -> 1/eta) is the internal diffuse reflectance.
//  * Sampling: specular lobe (visible normals, Heitz & d'Eon 2014) with probability
//    p_s = (1 - T(cos wi)) w / ((1 - T) w + T (1 - w)), w as in the smooth plastic;
//    else cosine-weighted. pdf = p_s D_wi(h) / (4 wo.h) + (1 - p_s) cos wo / pi
//    (Walter 2007, Eq. 14); weight = f cos / pdf of the mixture.
#include "core/error.h"
#include "core/warp.h"
#include "scene/bsdf/bsdf_detail.h"
#include "scene/bsdf/fresnel.h"
#include "scene/bsdf/microfacet.h"
#include "scene/bsdf/rough_transmittance.h"

namespace dp::scene {
namespace {

class RoughPlasticBsdf final : public Bsdf {
 public:
  RoughPlasticBsdf(TexturePtr kd, float eta, const Microfacet& d, bool nonlinear, TexturePtr ks)
      : m_kd(std::move(kd)),
        m_ks(std::move(ks)),
        m_eta(eta),
        m_distr(d),
        m_nonlinear(nonlinear),
        m_t_ext(d.type(), d.alpha_u(), eta) {
    m_fdr_int = 1.0f - RoughTransmittance(d.type(), d.alpha_u(), 1.0f / eta).diffuse();
    const float dl = luminance(m_kd->mean()), sl = luminance(detail::mean_or(m_ks));
    m_spec_weight = (dl + sl) > 0.0f ? sl / (dl + sl) : 0.5f;
  }

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    const Vec3 h = (wi + wo).normalized();
    Rgb f = Rgb::Zero();
    const float d = m_distr.D(h);
    if (d > 0.0f) {
      const float fr = fresnel_dielectric(wi.dot(h), m_eta).reflectance;
      // Walter 2007, Eq. 20.
      f += detail::eval_or(m_ks, ctx.uv) * (fr * d * m_distr.G(wi, wo, h) / (4.0f * wi.z() * wo.z()));
    }
    const Rgb rho = m_kd->eval(ctx.uv);
    const Rgb rho_eff = m_nonlinear ? Rgb(rho / (1.0f - rho * m_fdr_int)) : Rgb(rho / (1.0f - m_fdr_int));
    f += rho_eff * (kInvPi * m_t_ext.eval(wi.z()) * m_t_ext.eval(wo.z()) / sqr(m_eta));
    return f;
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return 0.0f;
    const float ps = prob_specular(wi.z());
    const Vec3 h = (wi + wo).normalized();
    return ps * m_distr.pdf_visible(wi, h) / (4.0f * wo.dot(h)) + (1.0f - ps) * wo.z() * kInvPi;
  }

  // eval() and pdf() sharing h, D(h), G1(wi, h) and T(cos wi); the same expressions in
  // the same order, so the values are those of the two separate calls.
  Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override {
    pdf_out = 0.0f;
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    const Vec3 h = (wi + wo).normalized();
    const float t_wi = m_t_ext.eval(wi.z());
    const float ps = prob_specular_from_t(t_wi);
    Rgb f = Rgb::Zero();
    const float d = m_distr.D(h);
    float pdf_visible = 0.0f;  // Heitz 2014, Eq. 17; 0 where D is
    if (d > 0.0f) {
      const float g1_wi = m_distr.G1(wi, h);
      pdf_visible = g1_wi * std::max(0.0f, wi.dot(h)) * d / wi.z();
      const float fr = fresnel_dielectric(wi.dot(h), m_eta).reflectance;
      // Walter 2007, Eq. 20.
      f += detail::eval_or(m_ks, ctx.uv) * (fr * d * (g1_wi * m_distr.G1(wo, h)) / (4.0f * wi.z() * wo.z()));
    }
    const Rgb rho = m_kd->eval(ctx.uv);
    const Rgb rho_eff = m_nonlinear ? Rgb(rho / (1.0f - rho * m_fdr_int)) : Rgb(rho / (1.0f - m_fdr_int));
    f += rho_eff * (kInvPi * t_wi * m_t_ext.eval(wo.z()) / sqr(m_eta));
    // Walter 2007, Eq. 14 for the specular lobe, cosine density for the diffuse one.
    pdf_out = ps * pdf_visible / (4.0f * wo.dot(h)) + (1.0f - ps) * wo.z() * kInvPi;
    return f;
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    BsdfSample s;
    if (u_lobe < prob_specular(wi.z())) {
      const Vec3 m = m_distr.sample_visible(wi, u);
      s.wo = (2.0f * wi.dot(m) * m - wi).normalized();
      s.lobe = kGlossyReflection;
    } else {
      s.wo = core::warp::square_to_cosine_hemisphere(u);
      s.lobe = kDiffuseReflection;
    }
    if (s.wo.z() <= 0.0f) return std::nullopt;
    const Rgb f = eval_pdf(ctx, wi, s.wo, s.pdf);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.weight = f * (s.wo.z() / s.pdf);
    return s;
  }

  float roughness() const override { return m_distr.alpha_u(); }
  uint32_t lobes() const override {
    return kGlossyReflection | (max_component(m_kd->max()) > 0.0f ? kDiffuseReflection : 0u);
  }
  std::string name() const override { return "roughplastic"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_kd->eval(ctx.uv) * m_t_ext.diffuse(); }
  bool has_texture() const override { return detail::varies(m_kd) || detail::varies(m_ks); }

 private:
  float prob_specular(float cos_i) const { return prob_specular_from_t(m_t_ext.eval(cos_i)); }
  float prob_specular_from_t(float t_cos_i) const {
    const float r = 1.0f - t_cos_i;
    const float a = r * m_spec_weight, b = (1.0f - r) * (1.0f - m_spec_weight);
    return (a + b) > 0.0f ? a / (a + b) : 0.0f;
  }

  TexturePtr m_kd, m_ks;
  float m_eta;
  Microfacet m_distr;
  bool m_nonlinear;
  RoughTransmittance m_t_ext;
  float m_fdr_int = 0, m_spec_weight = 0.5f;
};

}  // namespace

BsdfPtr detail::make_rough_plastic(TexturePtr diffuse, float int_ior, float ext_ior, float alpha,
                                   MicrofacetType dist, bool nonlinear, TexturePtr specular_reflectance) {
  return std::make_shared<RoughPlasticBsdf>(std::move(diffuse), int_ior / ext_ior, Microfacet(dist, alpha),
                                            nonlinear, std::move(specular_reflectance));
}

}  // namespace dp::scene
