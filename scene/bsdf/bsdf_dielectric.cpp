// Smooth dielectric interface and thin dielectric sheet.
// Dielectric (roughness 0): two Dirac lobes, reflection wo = reflect(wi) and refraction
// by Snell's law, chosen with probability F and 1 - F (exact Fresnel, fresnel.h), so
// both weights are the specular_reflectance / specular_transmittance factors; the
// refracted weight is additionally scaled by 1 / eta^2 in radiance mode, eta =
// eta_o / eta_i (Veach 1997, Sec. 5.2, Eq. 5.19: radiance is not symmetric under
// refraction). Two-sided: eta = int_ior / ext_ior when wi is on the normal's side,
// 1 / that otherwise. eval() and pdf() are 0. roughness > 0 dispatches to the Walter
// et al. 2007 rough dielectric (bsdf_rough_dielectric.cpp).
// Thin dielectric (Mitsuba "thindielectric"): a sheet with two parallel interfaces;
// summing the internal bounces gives R' = R + T^2 R / (1 - R^2) = 2R / (1 + R) and
// T' = 1 - R', with straight-through transmission wo = -wi (no refraction, eta = 1).
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"
#include "scene/bsdf/fresnel.h"

namespace dp::scene {
namespace {

class SmoothDielectricBsdf final : public Bsdf {
 public:
  SmoothDielectricBsdf(float eta, TexturePtr r, TexturePtr t) : m_eta(eta), m_r(std::move(r)), m_t(std::move(t)) {}

  Rgb eval(const BsdfContext&, const Vec3&, const Vec3&) const override { return Rgb::Zero(); }
  float pdf(const BsdfContext&, const Vec3&, const Vec3&) const override { return 0.0f; }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2&) const override {
    if (wi.z() == 0.0f) return std::nullopt;
    const DielectricFresnel fr = fresnel_dielectric(wi.z(), m_eta);
    BsdfSample s;
    if (u_lobe < fr.reflectance) {
      s.wo = detail::reflect_local(wi);
      s.pdf = fr.reflectance;
      s.weight = detail::eval_or(m_r, ctx.uv);
      s.lobe = kDeltaReflection;
      return s;
    }
    // Snell: tangential component scales by 1 / eta_ti, normal component is cos_t.
    s.wo = Vec3(-wi.x() / fr.eta_ti, -wi.y() / fr.eta_ti, fr.cos_t).normalized();
    s.pdf = 1.0f - fr.reflectance;
    s.weight = detail::eval_or(m_t, ctx.uv);
    if (ctx.mode == TransportMode::radiance) s.weight /= sqr(fr.eta_ti);
    s.eta = fr.eta_ti;
    s.lobe = kDeltaTransmission;
    return s;
  }

  float roughness() const override { return 0.0f; }
  uint32_t lobes() const override { return kDeltaReflection | kDeltaTransmission; }
  std::string name() const override { return "dielectric"; }
  Rgb albedo(const BsdfContext& ctx) const override { return detail::eval_or(m_t, ctx.uv); }
  bool has_texture() const override { return detail::varies(m_r) || detail::varies(m_t); }

 private:
  float m_eta;
  TexturePtr m_r, m_t;
};

class ThinDielectricBsdf final : public Bsdf {
 public:
  explicit ThinDielectricBsdf(float eta) : m_eta(eta) {}

  Rgb eval(const BsdfContext&, const Vec3&, const Vec3&) const override { return Rgb::Zero(); }
  float pdf(const BsdfContext&, const Vec3&, const Vec3&) const override { return 0.0f; }

  std::optional<BsdfSample> sample(const BsdfContext&, const Vec3& wi, float u_lobe, const Vec2&) const override {
    if (wi.z() == 0.0f) return std::nullopt;
    float r = fresnel_dielectric(std::abs(wi.z()), m_eta).reflectance;
    if (r < 1.0f) r = 2.0f * r / (1.0f + r);  // geometric series of internal bounces
    BsdfSample s;
    s.weight = Rgb::Ones();
    if (u_lobe < r) {
      s.wo = detail::reflect_local(wi);
      s.pdf = r;
      s.lobe = kDeltaReflection;
    } else {
      s.wo = -wi;
      s.pdf = 1.0f - r;
      s.lobe = kDeltaTransmission;
    }
    return s;
  }

  float roughness() const override { return 0.0f; }
  uint32_t lobes() const override { return kDeltaReflection | kDeltaTransmission; }
  std::string name() const override { return "thindielectric"; }
  Rgb albedo(const BsdfContext&) const override { return Rgb::Ones(); }

 private:
  float m_eta;
};

}  // namespace

BsdfPtr make_dielectric(float int_ior, float ext_ior, float roughness, MicrofacetType dist,
                        TexturePtr specular_reflectance, TexturePtr specular_transmittance) {
  DP_CHECK(int_ior > 0.0f && ext_ior > 0.0f, "dielectric: ior must be positive");
  DP_CHECK(roughness >= 0.0f, "dielectric: roughness must be >= 0");
  if (roughness > 0.0f)
    return detail::make_rough_dielectric(int_ior, ext_ior, roughness, dist, std::move(specular_reflectance),
                                         std::move(specular_transmittance));
  return std::make_shared<SmoothDielectricBsdf>(int_ior / ext_ior, std::move(specular_reflectance),
                                                std::move(specular_transmittance));
}

BsdfPtr make_thin_dielectric(float int_ior, float ext_ior) {
  DP_CHECK(int_ior > 0.0f && ext_ior > 0.0f, "thindielectric: ior must be positive");
  return std::make_shared<ThinDielectricBsdf>(int_ior / ext_ior);
}

}  // namespace dp::scene
