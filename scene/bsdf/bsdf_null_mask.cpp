// Null and mask (stochastic opacity) BSDFs.
// Null (Mitsuba "null"): a pass-through surface; one Dirac lobe wo = -wi of weight 1
// (pdf 1, lobe kNull, eta 1), eval() = pdf() = 0. Used for medium boundaries.
// Mask (Mitsuba "mask"): with opacity a(uv) (RGB), f = a f_inner plus a null lobe of
// weight 1 - a. The inner BSDF is chosen with probability p = mean(a) (clamped to
// [0, 1]); pdf() = p pdf_inner; sampled weights are rescaled by a / p and
// (1 - a) / (1 - p) so that they stay unbiased per channel.
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"

namespace dp::scene {
namespace {

BsdfSample pass_through(const Vec3& wi, const Rgb& weight, float pdf) {
  BsdfSample s;
  s.wo = -wi;
  s.weight = weight;
  s.pdf = pdf;
  s.eta = 1.0f;
  s.lobe = kNull;
  return s;
}

class NullBsdf final : public Bsdf {
 public:
  Rgb eval(const BsdfContext&, const Vec3&, const Vec3&) const override { return Rgb::Zero(); }
  float pdf(const BsdfContext&, const Vec3&, const Vec3&) const override { return 0.0f; }
  std::optional<BsdfSample> sample(const BsdfContext&, const Vec3& wi, float, const Vec2&) const override {
    return pass_through(wi, Rgb::Ones(), 1.0f);
  }
  float roughness() const override { return 0.0f; }
  uint32_t lobes() const override { return kNull; }
  std::string name() const override { return "null"; }
};

class MaskBsdf final : public Bsdf {
 public:
  MaskBsdf(BsdfPtr inner, TexturePtr opacity) : m_inner(std::move(inner)), m_opacity(std::move(opacity)) {}

  Rgb eval(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    return m_opacity->eval(ctx.uv) * m_inner->eval(ctx, wi, wo);
  }
  float pdf(const BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override {
    return prob(m_opacity->eval(ctx.uv)) * m_inner->pdf(ctx, wi, wo);
  }
  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                   const Vec2& u) const override {
    const Rgb a = m_opacity->eval(ctx.uv);
    const float p = prob(a);
    if (u_lobe < p) {
      auto s = m_inner->sample(ctx, wi, std::min(u_lobe / p, std::nextafter(1.0f, 0.0f)), u);
      if (!s) return std::nullopt;
      s->weight *= a / p;
      s->pdf *= p;
      return s;
    }
    return pass_through(wi, (Rgb::Ones() - a) / (1.0f - p), 1.0f - p);
  }

  float roughness() const override { return m_inner->roughness(); }
  float phong_exponent() const override { return m_inner->phong_exponent(); }
  uint32_t lobes() const override { return m_inner->lobes() | kNull; }
  std::string name() const override { return "mask(" + m_inner->name() + ")"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_opacity->eval(ctx.uv) * m_inner->albedo(ctx); }
  bool has_texture() const override { return detail::varies(m_opacity) || m_inner->has_texture(); }

 private:
  static float prob(const Rgb& a) { return std::clamp(a.mean(), 0.0f, 1.0f); }
  BsdfPtr m_inner;
  TexturePtr m_opacity;
};

}  // namespace

BsdfPtr make_null() { return std::make_shared<NullBsdf>(); }

BsdfPtr make_mask(BsdfPtr inner, TexturePtr opacity) {
  DP_CHECK(inner && opacity, "mask: inner BSDF and opacity required");
  return std::make_shared<MaskBsdf>(std::move(inner), std::move(opacity));
}

}  // namespace dp::scene
