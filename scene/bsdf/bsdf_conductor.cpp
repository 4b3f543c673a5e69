// Conductors.
// Smooth (alpha 0): one Dirac reflection lobe, weight = F(cos wi) * specular_reflectance,
// pdf = 1 (discrete). Rough: Cook-Torrance microfacet BRDF (Walter et al. 2007, Eq. 20)
//   f(wi, wo) = F(wi.h) D(h) G(wi, wo, h) / (4 cos wi cos wo),  h = normalize(wi + wo),
// with Beckmann or GGX D (isotropic or anisotropic alpha_u/alpha_v) and separable
// Smith G. Sampling: visible normals m ~ D_wi (Heitz & d'Eon 2014), wo = reflect(wi, m);
// pdf(wo) = D_wi(h) / (4 |wo.h|) (Walter 2007, Eq. 14 Jacobian); weight = F G1(wo)
// (Heitz & d'Eon 2014, Eq. 12). F is Schlick with RGB F0 or the exact complex-index
// conductor Fresnel. Both variants are one-sided (upper hemisphere).
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"
#include "scene/bsdf/fresnel.h"
#include "scene/bsdf/microfacet.h"

namespace dp::scene {
namespace {

Rgb conductor_fresnel(const ConductorFresnel& f, float cos_i) {
  return f.kind == ConductorFresnel::Kind::schlick ? fresnel_schlick(cos_i, f.f0)
                                                   : fresnel_conductor(cos_i, f.eta, f.k);
}

class SmoothConductorBsdf final : public Bsdf {
 public:
  SmoothConductorBsdf(const ConductorFresnel& f, TexturePtr spec) : m_fresnel(f), m_spec(std::move(spec)) {}

  Rgb eval(const BsdfContext&, const Vec3&, const Vec3&) const override { return Rgb::Zero(); }
  float pdf(const BsdfContext&, const Vec3&, const Vec3&) const override { return 0.0f; }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float, const Vec2&) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wo = detail::reflect_local(wi);
    s.pdf = 1.0f;
    s.weight = conductor_fresnel(m_fresnel, wi.z()) * detail::eval_or(m_spec, ctx.uv);
    s.lobe = kDeltaReflection;
    return s;
  }

  float roughness() const override { return 0.0f; }
  uint32_t lobes() const override { return kDeltaReflection; }
  std::string name() const override { return "conductor"; }
  Rgb albedo(const BsdfContext& ctx) const override {
    return conductor_fresnel(m_fresnel, 1.0f) * detail::eval_or(m_spec, ctx.uv);
  }
  bool has_texture() const override { return detail::varies(m_spec); }

 private:
  ConductorFresnel m_fresnel;
  TexturePtr m_spec;
};

class RoughConductorBsdf final : public Bsdf {
 public:
  RoughConductorBsdf(const Microfacet& d, const ConductorFresnel& f, TexturePtr spec)
      : m_distr(d), m_fresnel(f), m_spec(std::move(spec)) {}

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    const Vec3 h = (wi + wo).normalized();
    const float d = m_distr.D(h);
    if (d == 0.0f) return Rgb::Zero();
    const float g = m_distr.G(wi, wo, h);
    // Walter 2007, Eq. 20.
    return conductor_fresnel(m_fresnel, wi.dot(h)) * detail::eval_or(m_spec, ctx.uv) *
           (d * g / (4.0f * wi.z() * wo.z()));
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return 0.0f;
    const Vec3 h = (wi + wo).normalized();
    // Walter 2007, Eq. 14: dwh/dwo = 1 / (4 |wo.h|).
    return m_distr.pdf_visible(wi, h) / (4.0f * wo.dot(h));
  }

  // eval() and pdf() sharing h, D(h) and G1(wi, h); the same expressions in the same order.
  Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override {
    pdf_out = 0.0f;
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    const Vec3 h = (wi + wo).normalized();
    const float d = m_distr.D(h);
    if (d == 0.0f) return Rgb::Zero();  // pdf_visible is 0 too
    const float g1_wi = m_distr.G1(wi, h);
    // Heitz 2014, Eq. 17 (pdf_visible), Walter 2007, Eq. 14.
    pdf_out = g1_wi * std::max(0.0f, wi.dot(h)) * d / wi.z() / (4.0f * wo.dot(h));
    const float g = g1_wi * m_distr.G1(wo, h);
    // Walter 2007, Eq. 20.
    return conductor_fresnel(m_fresnel, wi.dot(h)) * detail::eval_or(m_spec, ctx.uv) *
           (d * g / (4.0f * wi.z() * wo.z()));
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float, const Vec2& u) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    const Vec3 m = m_distr.sample_visible(wi, u);
    const float c = wi.dot(m);
    if (c <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wo = (2.0f * c * m - wi).normalized();
    if (s.wo.z() <= 0.0f) return std::nullopt;
    s.pdf = pdf(ctx, wi, s.wo);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    // Heitz & d'Eon 2014, Eq. 12: f cos / pdf = F G1(wo).
    s.weight = conductor_fresnel(m_fresnel, c) * detail::eval_or(m_spec, ctx.uv) * m_distr.G1(s.wo, m);
    s.lobe = kGlossyReflection;
    return s;
  }

  float roughness() const override { return std::min(m_distr.alpha_u(), m_distr.alpha_v()); }
  uint32_t lobes() const override { return kGlossyReflection; }
  std::string name() const override { return "roughconductor"; }
  Rgb albedo(const BsdfContext& ctx) const override {
    return conductor_fresnel(m_fresnel, 1.0f) * detail::eval_or(m_spec, ctx.uv);
  }
  bool has_texture() const override { return detail::varies(m_spec); }

 private:
  Microfacet m_distr;
  ConductorFresnel m_fresnel;
  TexturePtr m_spec;
};

}  // namespace

BsdfPtr make_conductor(float alpha_u, float alpha_v, MicrofacetType dist, const ConductorFresnel& fresnel,
                       TexturePtr specular_reflectance) {
  DP_CHECK(alpha_u >= 0.0f && alpha_v >= 0.0f, "conductor: alpha must be >= 0");
  if (alpha_u == 0.0f && alpha_v == 0.0f)
    return std::make_shared<SmoothConductorBsdf>(fresnel, std::move(specular_reflectance));
  DP_CHECK(alpha_u > 0.0f && alpha_v > 0.0f, "conductor: either both or neither alpha may be 0");
  return std::make_shared<RoughConductorBsdf>(Microfacet(dist, alpha_u, alpha_v), fresnel,
                                              std::move(specular_reflectance));
}

}  // namespace dp::scene
