// Normalized modified Phong (Lafortune & Willems 1994, "Using the Modified Phong
// Reflectance Model for Physically Based Rendering", Eq. 6 normalization):
//   f(wi, wo) = kd / pi + ks (n + 2) / (2 pi) max(0, cos a)^n,
//   cos a = reflect(wi) . wo, one-sided (upper hemisphere).
// Energy: the specular albedo is at most ks (reached at normal incidence), so
// kd + ks <= 1 conserves energy.
// Sampling: the specular lobe with probability w_s = lum(mean ks) / (lum(mean kd) +
// lum(mean ks)), else cosine-weighted. Specular lobe: cos a = u^(1/(n+1)) around the
// mirror direction, density (n + 1) / (2 pi) cos^n a (Lafortune 1994, Eq. 8); samples
// below the horizon fail. pdf() is the mixture, weight = f |cos wo| / pdf.
// roughness() = sqrt(2 / (2 + n)), the Beckmann-equivalent alpha used by Mitsuba.
#include "core/error.h"
#include "core/warp.h"
#include "scene/bsdf/bsdf_detail.h"

namespace dp::scene {
namespace {

class PhongBsdf final : public Bsdf {
 public:
  PhongBsdf(TexturePtr kd, TexturePtr ks, float n) : m_kd(std::move(kd)), m_ks(std::move(ks)), m_n(n) {
    const float d = luminance(m_kd->mean()), s = luminance(m_ks->mean());
    m_spec_weight = (d + s) > 0.0f ? s / (d + s) : 0.5f;
  }

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    Rgb f = m_kd->eval(ctx.uv) * kInvPi;
    const float ca = detail::reflect_local(wi).dot(wo);
    if (ca > 0.0f) f += m_ks->eval(ctx.uv) * ((m_n + 2.0f) * kInv2Pi * std::pow(ca, m_n));
    return f;
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return 0.0f;
    return (1.0f - m_spec_weight) * wo.z() * kInvPi + m_spec_weight * pdf_specular(wi, wo);
  }

  // eval() and pdf() sharing the one pow(); the same expressions in the same order.
  Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override {
    pdf_out = 0.0f;
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    Rgb f = m_kd->eval(ctx.uv) * kInvPi;
    const float ca = detail::reflect_local(wi).dot(wo);
    float pdf_spec = 0.0f;
    if (ca > 0.0f) {
      const float p = std::pow(ca, m_n);
      f += m_ks->eval(ctx.uv) * ((m_n + 2.0f) * kInv2Pi * p);
      pdf_spec = (m_n + 1.0f) * kInv2Pi * p;
    }
    pdf_out = (1.0f - m_spec_weight) * wo.z() * kInvPi + m_spec_weight * pdf_spec;
    return f;
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    BsdfSample s;
    if (u_lobe < m_spec_weight) {
      const float ca = std::pow(u.x(), 1.0f / (m_n + 1.0f));
      const float sa = safe_sqrt(1.0f - ca * ca);
      const float phi = 2.0f * kPi * u.y();
      const Frame fr = Frame::from_normal(detail::reflect_local(wi));
      s.wo = fr.to_world(Vec3(sa * std::cos(phi), sa * std::sin(phi), ca));
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

  float roughness() const override {
    return max_component(m_ks->max()) > 0.0f ? std::sqrt(2.0f / (2.0f + m_n)) : kDiffuseRoughness;
  }
  float phong_exponent() const override { return max_component(m_ks->max()) > 0.0f ? m_n : 0.0f; }
  uint32_t lobes() const override {
    uint32_t l = 0;
    if (max_component(m_kd->max()) > 0.0f) l |= kDiffuseReflection;
    if (max_component(m_ks->max()) > 0.0f) l |= kGlossyReflection;
    return l;
  }
  std::string name() const override { return "phong"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_kd->eval(ctx.uv) + m_ks->eval(ctx.uv); }
  bool has_texture() const override { return detail::varies(m_kd) || detail::varies(m_ks); }

 private:
  float pdf_specular(const Vec3& wi, const Vec3& wo) const {
    const float ca = detail::reflect_local(wi).dot(wo);
    return ca > 0.0f ? (m_n + 1.0f) * kInv2Pi * std::pow(ca, m_n) : 0.0f;
  }

  TexturePtr m_kd, m_ks;
  float m_n;
  float m_spec_weight = 0.5f;
};

}  // namespace

BsdfPtr make_phong(TexturePtr diffuse, TexturePtr specular, float exponent) {
  DP_CHECK(diffuse && specular, "phong: textures required");
  DP_CHECK(exponent >= 0.0f && std::isfinite(exponent), "phong: exponent must be >= 0");
  return std::make_shared<PhongBsdf>(std::move(diffuse), std::move(specular), exponent);
}

}  // namespace dp::scene
