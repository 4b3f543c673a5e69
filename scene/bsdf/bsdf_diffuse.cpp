// Lambertian reflection: f = albedo / pi on the upper hemisphere (one-sided).
// Sampling: cosine-weighted hemisphere, pdf = cos(wo) / pi, so weight = albedo.
#include "core/error.h"
#include "core/warp.h"
#include "scene/bsdf/bsdf_detail.h"

namespace dp::scene {
namespace {

class DiffuseBsdf final : public Bsdf {
 public:
  explicit DiffuseBsdf(TexturePtr albedo) : m_albedo(std::move(albedo)) {}

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return Rgb::Zero();
    return m_albedo->eval(ctx.uv) * kInvPi;
  }

  float pdf(const BsdfContext&, const Vec3& wi, const Vec3& wo) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) return 0.0f;
    return core::warp::square_to_cosine_hemisphere_pdf(wo);
  }

  Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override {
    if (wi.z() <= 0.0f || wo.z() <= 0.0f) {
      pdf_out = 0.0f;
      return Rgb::Zero();
    }
    pdf_out = core::warp::square_to_cosine_hemisphere_pdf(wo);
    return m_albedo->eval(ctx.uv) * kInvPi;
  }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float, const Vec2& u) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wo = core::warp::square_to_cosine_hemisphere(u);
    s.pdf = core::warp::square_to_cosine_hemisphere_pdf(s.wo);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.weight = m_albedo->eval(ctx.uv);  // (albedo / pi) cos / (cos / pi)
    s.lobe = kDiffuseReflection;
    return s;
  }

  float roughness() const override { return kDiffuseRoughness; }
  uint32_t lobes() const override { return kDiffuseReflection; }
  std::string name() const override { return "diffuse"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_albedo->eval(ctx.uv); }
  bool has_texture() const override { return detail::varies(m_albedo); }

 private:
  TexturePtr m_albedo;
};

}  // namespace

BsdfPtr make_diffuse(TexturePtr albedo) {
  DP_CHECK(albedo != nullptr, "diffuse: albedo texture required");
  return std::make_shared<DiffuseBsdf>(std::move(albedo));
}

}  // namespace dp::scene
