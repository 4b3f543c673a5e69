// Smooth plastic: a diffuse base under a smooth dielectric coating, following the
// semantics of Mitsuba 0.6 "plastic" (Weidlich & Wilkie 2007, "Arbitrarily Layered
// Micro-Facet Surfaces", Sec. 3, for the layering approximation). One-sided.
//  * Specular: a Dirac reflection of weight Fi * specular_reflectance, Fi = F(cos wi).
//  * Diffuse: light refracts in (1 - Fi), bounces inside the layer between the base
//    (albedo rho) and the coating (internal diffuse Fresnel reflectance Fdr_int), and
//    refracts out (1 - Fo) with the radiance compression 1 / eta^2:
//      f_d = rho' / pi * (1 - Fi) (1 - Fo) / eta^2,
//    rho' = rho / (1 - Fdr_int) by default (each bounce is white), or with
//    nonlinear = true the geometric series of coloured bounces rho / (1 - rho Fdr_int)
//    (which shifts saturated albedos, as in Mitsuba's `nonlinear`).
//  * Sampling: the specular lobe with probability p_s = Fi w / (Fi w + (1 - Fi)(1 - w)),
//    w = lum(mean spec) / (lum(mean spec) + lum(mean diffuse)); else cosine-weighted.
//    pdf() = (1 - p_s) cos(wo) / pi (the delta lobe is excluded).
// roughness > 0 dispatches to the rough plastic (bsdf_rough_plastic.cpp).
#include "core/error.h"
#include "core/warp.h"
#include "scene/bsdf/bsdf_detail.h"
#include "scene/bsdf/fresnel.h"

namespace dp::scene {
namespace {

class SmoothPlasticBsdf final : public Bsdf {
 public:
  SmoothPlasticBsdf(TexturePtr kd, float eta, bool nonlinear, TexturePtr ks)
      : m_kd(std::move(kd)), m_ks(std::move(ks)), m_eta(eta), m_nonlinear(nonlinear) {
    m_fdr_int = fresnel_diffuse_reflectance(1.0f / eta);
    m_fdr_ext = fresnel_diffuse_reflectance(eta);
    const float d = luminance(m_kd->mean()), s = luminance(detail::mean_or(m_ks));
    m_spec_weight = (d + s) > 0.0f ? s / (d + s) : 0.5f;
  }

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    const float fi = fresnel_dielectric(wi.z(), m_eta).reflectance;
    const float fo = fresnel_dielectric(wo.z(), m_eta).reflectance;
    return diffuse_term(ctx) * (kInvPi * (1.0f - fi) * (1.0f - fo) / sqr(m_eta));
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return 0.0f;
    const float fi = fresnel_dielectric(wi.z(), m_eta).reflectance;
    return (1.0f - prob_specular(fi)) * wo.z() * kInvPi;
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    const float fi = fresnel_dielectric(wi.z(), m_eta).reflectance;
    const float ps = prob_specular(fi);
    BsdfSample s;
    if (u_lobe < ps) {
      s.wo = detail::reflect_local(wi);
      s.pdf = ps;
      s.weight = detail::eval_or(m_ks, ctx.uv) * (fi / ps);
      s.lobe = kDeltaReflection;
      return s;
    }
    s.wo = core::warp::square_to_cosine_hemisphere(u);
    s.pdf = pdf(ctx, wi, s.wo);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.weight = eval(ctx, wi, s.wo) * (s.wo.z() / s.pdf);
    s.lobe = kDiffuseReflection;
    return s;
  }

  float roughness() const override { return has_diffuse() ? kDiffuseRoughness : 0.0f; }
  uint32_t lobes() const override { return kDeltaReflection | (has_diffuse() ? kDiffuseReflection : 0u); }
  std::string name() const override { return "plastic"; }
  // Diffuse-like reflectance seen from outside (Mitsuba: rho (1 - Fdr_ext)).
  Rgb albedo(const BsdfContext& ctx) const override { return m_kd->eval(ctx.uv) * (1.0f - m_fdr_ext); }
  bool has_texture() const override { return detail::varies(m_kd) || detail::varies(m_ks); }

 private:
  bool has_diffuse() const { return max_component(m_kd->max()) > 0.0f; }
  float prob_specular(float fi) const {
    const float a = fi * m_spec_weight, b = (1.0f - fi) * (1.0f - m_spec_weight);
    return (a + b) > 0.0f ? a / (a + b) : 0.0f;
  }
  Rgb diffuse_term(const BsdfContext& ctx) const {
    const Rgb rho = m_kd->eval(ctx.uv);
    return m_nonlinear ? Rgb(rho / (1.0f - rho * m_fdr_int)) : Rgb(rho / (1.0f - m_fdr_int));
  }

  TexturePtr m_kd, m_ks;
  float m_eta;
  bool m_nonlinear;
  float m_fdr_int = 0, m_fdr_ext = 0, m_spec_weight = 0.5f;
};

}  // namespace

BsdfPtr make_plastic(TexturePtr diffuse, float int_ior, float ext_ior, float roughness, MicrofacetType dist,
                     bool nonlinear, TexturePtr specular_reflectance) {
  DP_CHECK(diffuse != nullptr, "plastic: diffuse texture required");
  DP_CHECK(int_ior > 0.0f && ext_ior > 0.0f && int_ior != ext_ior, "plastic: iors must be positive and differ");
  DP_CHECK(roughness >= 0.0f, "plastic: roughness must be >= 0");
  if (roughness > 0.0f)
    return detail::make_rough_plastic(std::move(diffuse), int_ior, ext_ior, roughness, dist, nonlinear,
                                      std::move(specular_reflectance));
  return std::make_shared<SmoothPlasticBsdf>(std::move(diffuse), int_ior / ext_ior, nonlinear,
                                             std::move(specular_reflectance));
}

}  // namespace dp::scene
