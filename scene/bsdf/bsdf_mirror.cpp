// Ideal mirror: a single Dirac reflection lobe wo = (-wi.x, -wi.y, wi.z) with
// reflectance R (no Fresnel). One-sided: wi below the surface scatters nothing.
// eval() and pdf() are 0 (delta lobe); sample() returns pdf = 1 (discrete lobe
// probability) and weight = R.
#include "core/error.h"
#include "scene/bsdf/bsdf_detail.h"

namespace dp::scene {
namespace {

class MirrorBsdf final : public Bsdf {
 public:
  explicit MirrorBsdf(TexturePtr r) : m_r(std::move(r)) {}

  Rgb eval(const BsdfContext&, const Vec3&, const Vec3&) const override { return Rgb::Zero(); }
  float pdf(const BsdfContext&, const Vec3&, const Vec3&) const override { return 0.0f; }

  std::optional<BsdfSample> sample(const BsdfContext& ctx, const Vec3& wi, float, const Vec2&) const override {
    if (wi.z() <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wo = detail::reflect_local(wi);
    s.pdf = 1.0f;
    s.weight = m_r->eval(ctx.uv);
    s.lobe = kDeltaReflection;
    return s;
  }

  float roughness() const override { return 0.0f; }
  uint32_t lobes() const override { return kDeltaReflection; }
  std::string name() const override { return "mirror"; }
  Rgb albedo(const BsdfContext& ctx) const override { return m_r->eval(ctx.uv); }
  bool has_texture() const override { return detail::varies(m_r); }

 private:
  TexturePtr m_r;
};

}  // namespace

BsdfPtr make_mirror(TexturePtr reflectance) {
  DP_CHECK(reflectance != nullptr, "mirror: reflectance texture required");
  return std::make_shared<MirrorBsdf>(std::move(reflectance));
}

}  // namespace dp::scene
