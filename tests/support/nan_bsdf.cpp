#include "tests/support/nan_bsdf.h"

#include <bit>
#include <cmath>
#include <limits>

namespace dp::test {

namespace {
// splitmix64 finalizer: a bijective mix, so nearby float bit patterns map to unrelated
// 64-bit values (uniform enough for a Bernoulli(p) decision per direction).
uint64_t mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

const float kNan = std::numeric_limits<float>::quiet_NaN();
}  // namespace

NanBsdf::NanBsdf(scene::BsdfPtr inner, double p) : m_inner(std::move(inner)), m_always(p >= 1.0) {
  const double clamped = std::fmin(std::fmax(p, 0.0), 1.0);
  m_threshold = m_always ? ~uint64_t(0) : uint64_t(std::ldexp(clamped, 64));
}

bool NanBsdf::poisoned(const Vec3& wi) const {
  if (m_always) return true;
  uint64_t h = 0x6A09E667F3BCC909ull;
  for (int i = 0; i < 3; ++i) h = mix(h ^ std::bit_cast<uint32_t>(wi[i]));
  return h < m_threshold;
}

Rgb NanBsdf::eval(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const {
  if (poisoned(wi)) {
    m_injected.fetch_add(1, std::memory_order_relaxed);
    return Rgb::Constant(kNan);
  }
  return m_inner->eval(ctx, wi, wo);
}

float NanBsdf::pdf(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const {
  return m_inner->pdf(ctx, wi, wo);
}

Rgb NanBsdf::eval_pdf(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const {
  const Rgb f = m_inner->eval_pdf(ctx, wi, wo, pdf_out);
  if (poisoned(wi)) {
    m_injected.fetch_add(1, std::memory_order_relaxed);
    return Rgb::Constant(kNan);
  }
  return f;
}

std::optional<scene::BsdfSample> NanBsdf::sample(const scene::BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                                 const Vec2& u) const {
  auto s = m_inner->sample(ctx, wi, u_lobe, u);
  if (s && poisoned(wi)) {
    m_injected.fetch_add(1, std::memory_order_relaxed);
    s->weight = Rgb::Constant(kNan);
  }
  return s;
}

}  // namespace dp::test
