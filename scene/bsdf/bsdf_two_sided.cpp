// Two-sided adapter: evaluates and samples `inner` (a reflection-only BSDF defined on
// the upper hemisphere) on whichever side wi lies, by mirroring both directions
// through the tangent plane (z -> -z) when wi.z < 0. Directions on opposite sides
// evaluate to 0 (the inner BSDF has no transmission). Everything else (lobes,
// roughness, albedo) is the inner BSDF's.
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"

namespace dp::scene {
namespace {

inline Vec3 flip(const Vec3& w) { return Vec3(w.x(), w.y(), -w.z()); }

class TwoSidedBsdf final : public Bsdf {
 public:
  explicit TwoSidedBsdf(BsdfPtr inner) : m_inner(std::move(inner)) {}

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    return wi.z() < 0.0f ? m_inner->eval(ctx, flip(wi), flip(wo)) : m_inner->eval(ctx, wi, wo);
  }
  float pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    return wi.z() < 0.0f ? m_inner->pdf(ctx, flip(wi), flip(wo)) : m_inner->pdf(ctx, wi, wo);
  }
  Rgb eval_pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override {
    return wi.z() < 0.0f ? m_inner->eval_pdf(ctx, flip(wi), flip(wo), pdf_out) : m_inner->eval_pdf(ctx, wi, wo, pdf_out);
  }
  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    if (wi.z() >= 0.0f) return m_inner->sample(ctx, wi, u_lobe, u);
    auto s = m_inner->sample(ctx, flip(wi), u_lobe, u);
    if (s) s->wo = flip(s->wo);
    return s;
  }

  float roughness() const override { return m_inner->roughness(); }
  float phong_exponent() const override { return m_inner->phong_exponent(); }
  uint32_t lobes() const override { return m_inner->lobes(); }
  std::string name() const override { return "twosided(" + m_inner->name() + ")"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_inner->albedo(ctx); }
  bool has_texture() const override { return m_inner->has_texture(); }

 private:
  BsdfPtr m_inner;
};

}  // namespace

BsdfPtr make_two_sided(BsdfPtr inner) {
  DP_CHECK(inner != nullptr, "twosided: inner BSDF required");
  DP_CHECK((inner->lobes() & kTransmission) == 0, "twosided: inner BSDF must be reflection-only");
  return std::make_shared<TwoSidedBsdf>(std::move(inner));
}

}  // namespace dp::scene
