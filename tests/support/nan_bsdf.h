// Test-only BSDF for NaN-injection tests: wraps a real BSDF and, for a fraction p of the
// surface points it is asked about, returns NaN from eval(), eval_pdf() (the value) and
// sample() (the weight). The decision is a pure function of the float bits of `wi`
// (a 64-bit mix hash, compared with p * 2^64), so:
//  * it is reproducible (same path -> same decision, whatever the thread or call order),
//  * it is thread-safe (no state but the atomic counter),
//  * every call at one path vertex (NEE eval, BSDF sample, MIS pdf) agrees: one vertex is
//    one Bernoulli(p) trial, which the binomial bounds of test_nan_injection.cpp rely on.
// pdf() is left finite (it is a density, the integrators' NaN guards are on values).
// Every call that returned a NaN is counted (injected()).
#pragma once

#include <atomic>
#include <cstdint>

#include "scene/bsdf/bsdf.h"

namespace dp::test {

class NanBsdf final : public scene::Bsdf {
 public:
  // p in [0, 1]: probability that a vertex (a given wi) returns NaN.
  NanBsdf(scene::BsdfPtr inner, double p);

  Rgb eval(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override;
  float pdf(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo) const override;
  Rgb eval_pdf(const scene::BsdfContext& ctx, const Vec3& wi, const Vec3& wo, float& pdf_out) const override;
  std::optional<scene::BsdfSample> sample(const scene::BsdfContext& ctx, const Vec3& wi, float u_lobe,
                                          const Vec2& u) const override;
  float roughness() const override { return m_inner->roughness(); }
  float phong_exponent() const override { return m_inner->phong_exponent(); }
  uint32_t lobes() const override { return m_inner->lobes(); }
  std::string name() const override { return "nan(" + m_inner->name() + ")"; }
  Rgb albedo(const scene::BsdfContext& ctx) const override { return m_inner->albedo(ctx); }
  bool has_texture() const override { return m_inner->has_texture(); }

  // Whether a vertex with this wi returns NaN (pure function of wi's bits and p).
  bool poisoned(const Vec3& wi) const;
  // Calls that returned a NaN so far (eval, eval_pdf and sample).
  int64_t injected() const { return m_injected.load(std::memory_order_relaxed); }
  void reset_count() { m_injected.store(0, std::memory_order_relaxed); }

 private:
  scene::BsdfPtr m_inner;
  uint64_t m_threshold;  // poisoned iff hash(wi) < threshold; p = threshold / 2^64
  bool m_always;         // p == 1
  mutable std::atomic<int64_t> m_injected{0};
};

}  // namespace dp::test
