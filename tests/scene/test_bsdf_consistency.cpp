// Deterministic consistency of every BSDF: sample() weight == eval |cos| / pdf and
// sample().pdf == pdf() for non-delta samples; delta samples carry the discrete lobe
// probability; reciprocity eval(wi, wo) == eval(wo, wi) for reflection BSDFs and the
// generalized rule for rough refraction (Veach 1997, Eq. 5.14 / 5.19).
// Tolerances are float round-off (relative 1e-3: the half vector is recomputed from
// the sampled wo, which loses ~1e-6 relative precision and D amplifies it by 1/alpha^2).
#include <catch2/catch.hpp>

#include "core/warp.h"
#include "tests/scene/bsdf_test_cases.h"

using namespace dp;
using namespace dp::scene;

namespace {
bool close(float a, float b, float rel, float abs_tol = 1e-6f) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs_tol;
}
bool close(const Rgb& a, const Rgb& b, float rel, float abs_tol = 1e-6f) {
  for (int c = 0; c < 3; ++c)
    if (!close(a[c], b[c], rel, abs_tol)) return false;
  return true;
}
// Refraction values far in the tails (h nearly perpendicular to wo, or wi.h near the
// critical angle) are computed from two differently rounded half vectors; there
// float round-off reaches ~1e-5 sr^-1 while lobe peaks are >= 0.1 sr^-1.
constexpr float kTailAbs = 1e-4f;
}  // namespace

TEST_CASE("sample() weight and pdf agree with eval() and pdf()", "[unit]") {
  for (const auto& c : test::bsdf_cases())
    for (TransportMode mode : {TransportMode::radiance, TransportMode::importance})
      for (const Vec3& wi : test::incident_dirs(c)) {
        BsdfContext ctx;
        ctx.mode = mode;
        core::Rng rng(5, 3);
        int bad = 0, total = 0;
        std::string first_bad;
        for (int k = 0; k < 4000; ++k) {
          const float ul = rng.uniform();
          const auto s = c.bsdf->sample(ctx, wi, ul, rng.uniform2());
          if (!s) continue;
          ++total;
          const bool ok_dir = std::abs(s->wo.norm() - 1.0f) < 1e-4f && is_finite(s->weight) &&
                              (s->weight >= 0.0f).all() && s->pdf > 0.0f && (s->lobe & c.bsdf->lobes()) != 0;
          bool ok = ok_dir;
          if (ok && !s->is_delta()) {
            const float p = c.bsdf->pdf(ctx, wi, s->wo);
            const Rgb f = c.bsdf->eval(ctx, wi, s->wo);
            ok = close(s->pdf, p, 1e-3f) && close(s->weight, Rgb(f * std::abs(s->wo.z()) / p), 1e-3f);
          }
          if (ok && s->is_delta()) ok = s->pdf <= 1.0f + 1e-6f;
          if (ok && (s->lobe & (kGlossyTransmission | kDeltaTransmission))) ok = s->wo.z() * wi.z() < 0.0f;
          if (ok && (s->lobe & (kGlossyReflection | kDeltaReflection | kDiffuseReflection)))
            ok = s->wo.z() * wi.z() > 0.0f && s->eta == 1.0f;
          if (!ok) {
            ++bad;
            if (first_bad.empty())
              first_bad = "wo=(" + std::to_string(s->wo.x()) + "," + std::to_string(s->wo.y()) + "," +
                          std::to_string(s->wo.z()) + ") pdf=" + std::to_string(s->pdf) + " lobe=" +
                          std::to_string(s->lobe);
          }
        }
        INFO(c.name << " wi=(" << wi.transpose() << ") mode " << int(mode) << ": " << bad << " of " << total
                    << " inconsistent, first " << first_bad);
        CHECK(bad == 0);
      }
}

// eval_pdf() is a fused eval() + pdf() (next-event estimation with MIS needs both); the
// overrides reuse h, D, G1(wi), pow() and must return the same two values. They are
// written as the same expressions in the same order, so the only allowed difference is
// a compiler's contraction into FMAs (a few ulps).
TEST_CASE("eval_pdf() returns eval() and pdf()", "[unit]") {
  for (const auto& c : test::bsdf_cases())
    for (TransportMode mode : {TransportMode::radiance, TransportMode::importance})
      for (const Vec3& wi : test::incident_dirs(c)) {
        BsdfContext ctx;
        ctx.mode = mode;
        ctx.uv = Vec2(0.3f, 0.7f);
        core::Rng rng(17, 4);
        int bad = 0, nonzero = 0;
        for (int k = 0; k < 2000; ++k) {
          // Directions from the BSDF's own sampler (where its values are large) and
          // uniform ones (tails, back side, below the horizon).
          Vec3 wo = core::warp::square_to_uniform_sphere(rng.uniform2());
          if (k % 2 == 0)
            if (const auto s = c.bsdf->sample(ctx, wi, rng.uniform(), rng.uniform2()); s && !s->is_delta()) wo = s->wo;
          float p_fused = -1.0f;
          const Rgb f_fused = c.bsdf->eval_pdf(ctx, wi, wo, p_fused);
          const float p = c.bsdf->pdf(ctx, wi, wo);
          const Rgb f = c.bsdf->eval(ctx, wi, wo);
          if (p > 0.0f) ++nonzero;
          if (!close(p_fused, p, 1e-5f, 0.0f) || !close(f_fused, f, 1e-5f, 0.0f)) ++bad;
        }
        INFO(c.name << " wi=(" << wi.transpose() << ") mode " << int(mode) << ": " << bad << " mismatches");
        CHECK(bad == 0);
        if (!c.bsdf->is_purely_delta()) CHECK(nonzero > 0);  // the comparison was not vacuous
      }
}

TEST_CASE("delta lobes: eval and pdf are zero, directions are exact", "[unit]") {
  BsdfContext ctx;
  const Vec3 wi = test::dir_from(0.6f, 0.8f);
  auto mirror = make_mirror(constant_texture(Rgb(0.9f, 0.8f, 0.7f)));
  auto s = mirror->sample(ctx, wi, 0.5f, Vec2(0.3f, 0.3f));
  REQUIRE(s);
  CHECK(s->wo.isApprox(Vec3(-wi.x(), -wi.y(), wi.z())));
  CHECK(s->pdf == 1.0f);
  CHECK(s->weight.isApprox(Rgb(0.9f, 0.8f, 0.7f)));
  CHECK(mirror->eval(ctx, wi, s->wo).isZero());
  CHECK(mirror->pdf(ctx, wi, s->wo) == 0.0f);
  CHECK(mirror->roughness() == 0.0f);
  CHECK(mirror->is_purely_delta());
  auto null = make_null();
  s = null->sample(ctx, wi, 0.5f, Vec2(0.3f, 0.3f));
  REQUIRE(s);
  CHECK(s->wo.isApprox(-wi));
  CHECK(s->lobe == kNull);
  // Smooth dielectric: Snell's law and eta.
  auto glass = make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx);
  s = glass->sample(ctx, wi, 0.99f, Vec2(0.5f, 0.5f));
  REQUIRE(s);
  CHECK(s->lobe == kDeltaTransmission);
  CHECK(s->eta == Approx(1.5f));
  const float sin_i = std::sqrt(1 - wi.z() * wi.z()), sin_t = std::sqrt(1 - s->wo.z() * s->wo.z());
  CHECK(sin_i == Approx(1.5f * sin_t).epsilon(1e-5));
  CHECK(s->weight[0] == Approx(1.0f / (1.5f * 1.5f)));  // radiance mode: 1 / eta^2
  // From inside beyond the critical angle: total internal reflection only.
  const Vec3 wi_in = test::dir_from(-0.3f, 0.1f);
  for (float ul : {0.0f, 0.5f, 0.999f}) {
    s = glass->sample(ctx, wi_in, ul, Vec2(0.5f, 0.5f));
    REQUIRE(s);
    CHECK(s->lobe == kDeltaReflection);
  }
  // Classification helpers.
  CHECK(make_diffuse(constant_texture(Rgb::Ones()))->roughness() == kDiffuseRoughness);
  CHECK(make_phong(constant_texture(Rgb::Zero()), constant_texture(Rgb::Ones()), 98.0f)->roughness() ==
        Approx(std::sqrt(2.0f / 100.0f)));
  CHECK(make_conductor(0.1f, 0.3f, MicrofacetType::ggx, ConductorFresnel{})->roughness() == Approx(0.1f));
}

TEST_CASE("reciprocity of reflection BSDFs and generalized reciprocity of refraction", "[unit]") {
  core::Rng rng(17, 0);
  BsdfContext rad, imp;
  imp.mode = TransportMode::importance;
  for (const auto& c : test::bsdf_cases()) {
    if (c.bsdf->is_purely_delta()) continue;
    int bad = 0;
    for (int k = 0; k < 3000; ++k) {
      const Vec3 a = core::warp::square_to_uniform_sphere(rng.uniform2());
      const Vec3 b = core::warp::square_to_uniform_sphere(rng.uniform2());
      if (c.reflection_only) {
        if (!close(c.bsdf->eval(rad, a, b), c.bsdf->eval(rad, b, a), 1e-3f)) ++bad;
        continue;
      }
      if (c.eta == 0.0f) continue;  // masks: reciprocal iff their inner BSDF is (tested above)
      // f_radiance(wi, wo) = f_importance(wo, wi); f_imp(wi,wo) / eta_o^2 = f_imp(wo,wi) / eta_i^2.
      if (!close(c.bsdf->eval(rad, a, b), c.bsdf->eval(imp, b, a), 1e-3f, kTailAbs)) {
        ++bad;
        UNSCOPED_INFO("a=(" << a.transpose() << ") b=(" << b.transpose() << ") f=" << c.bsdf->eval(rad, a, b)[0]
                            << " vs " << c.bsdf->eval(imp, b, a)[0]);
      }
      const float eta = c.eta;
      const float ea = a.z() > 0 ? 1.0f : eta, eb = b.z() > 0 ? 1.0f : eta;  // index on each side
      if (!close(c.bsdf->eval(imp, a, b) / (eb * eb), c.bsdf->eval(imp, b, a) / (ea * ea), 1e-3f, kTailAbs)) ++bad;
    }
    INFO(c.name << ": " << bad << " violations");
    CHECK(bad == 0);
  }
}
