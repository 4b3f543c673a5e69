// Energy tests: directional albedo <= 1 (within 4 standard errors) for every BSDF and
// many incident directions; albedo from sample() weights equals an independent
// uniform-direction estimate of \int f |cos| (within 4 combined standard errors);
// white furnace of the diffuse BSDF; smooth dielectric R + T = 1.
// Dielectrics are tested in importance mode (physical energy); in radiance mode the
// 1/eta^2 factor legitimately exceeds 1 when leaving the denser medium.
#include <catch2/catch.hpp>
#include <iostream>

#include "scene/bsdf/fresnel.h"
#include "tests/scene/bsdf_test_cases.h"

using namespace dp;
using namespace dp::scene;

namespace {
// The acceptance rules of the two albedo tests below, shared with the broken variants.
// Albedo <= 1 within 4 standard errors of the sampled estimate.
bool albedo_at_most_one(const test::AlbedoEstimate& a) { return a.mean <= 1.0 + 4.0 * a.std_error + 1e-5; }
// Sampled and uniform estimates agree within 4 combined standard errors.
bool estimates_agree(const test::AlbedoEstimate& s, const test::AlbedoEstimate& u) {
  return std::abs(s.mean - u.mean) <= 4.0 * std::sqrt(sqr(s.std_error) + sqr(u.std_error)) + 1e-6;
}
}  // namespace

TEST_CASE("albedo <= 1 for every BSDF and incident direction", "[stat]") {
  double worst = 0;
  std::string worst_name;
  uint64_t seed = 1;
  for (const auto& c : test::bsdf_cases()) {
    BsdfContext ctx;
    ctx.mode = TransportMode::importance;
    std::vector<Vec3> dirs = test::incident_dirs(c);
    for (float ct : {0.95f, 0.5f, 0.15f, 0.01f}) {
      dirs.push_back(test::dir_from(ct, 1.1f));
      if (c.two_sided_dir) dirs.push_back(test::dir_from(-ct, 2.1f));
    }
    for (const Vec3& wi : dirs) {
      const auto a = test::albedo_by_sampling(*c.bsdf, ctx, wi, 20000, seed++);
      INFO(c.name << " wi=(" << wi.transpose() << ") albedo " << a.mean << " +- " << a.std_error);
      CHECK(albedo_at_most_one(a));
      if (a.mean > worst) {
        worst = a.mean;
        worst_name = c.name;
      }
    }
  }
  std::cout << "[bsdf energy] max albedo " << worst << " (" << worst_name << ")\n";
}

TEST_CASE("albedo from sample() weights equals an independent estimate", "[stat]") {
  // Only broad lobes: the uniform estimator of a narrow lobe has a heavy-tailed
  // distribution whose sample standard error is unreliable.
  const auto tex = [](float v) { return constant_texture(Rgb::Constant(v)); };
  ConductorFresnel schlick;
  schlick.f0 = Rgb(0.9f, 0.6f, 0.5f);
  const std::vector<std::pair<std::string, BsdfPtr>> bsdfs = {
      {"diffuse", make_diffuse(tex(0.6f))},
      {"phong n=1", make_phong(tex(0.2f), tex(0.7f), 1.0f)},
      {"phong n=10", make_phong(tex(0.2f), tex(0.7f), 10.0f)},
      {"conductor beckmann 0.6", make_conductor(0.6f, 0.6f, MicrofacetType::beckmann, schlick)},
      {"conductor ggx 1.0", make_conductor(1.0f, 1.0f, MicrofacetType::ggx, schlick)},
      {"conductor ggx 0.5x0.9", make_conductor(0.5f, 0.9f, MicrofacetType::ggx, schlick)},
      {"roughdielectric beckmann 1.0", make_dielectric(1.5f, 1.0f, 1.0f, MicrofacetType::beckmann)},
      {"roughdielectric ggx 0.7", make_dielectric(1.33f, 1.0f, 0.7f, MicrofacetType::ggx)},
      {"roughplastic beckmann 0.8", make_plastic(tex(0.5f), 1.5f, 1.0f, 0.8f, MicrofacetType::beckmann)},
      {"roughplastic ggx 0.6 nonlinear", make_plastic(tex(0.7f), 1.5f, 1.0f, 0.6f, MicrofacetType::ggx, true)},
  };
  uint64_t seed = 500;
  for (const auto& [name, b] : bsdfs)
    for (TransportMode mode : {TransportMode::radiance, TransportMode::importance})
      for (float ct : {0.9f, 0.5f, 0.2f, -0.4f, -0.8f}) {
        if (ct < 0 && !(b->lobes() & kTransmission)) continue;
        BsdfContext ctx;
        ctx.mode = mode;
        const Vec3 wi = test::dir_from(ct, 0.3f);
        const auto s = test::albedo_by_sampling(*b, ctx, wi, 50000, seed++);
        const auto u = test::albedo_by_uniform(*b, ctx, wi, 200000, seed++);
        INFO(name << " cos " << ct << " mode " << int(mode) << ": sampled " << s.mean << " +- " << s.std_error
                  << ", uniform " << u.mean << " +- " << u.std_error);
        CHECK(estimates_agree(s, u));
      }
}

TEST_CASE("white furnace: diffuse albedo is reproduced", "[stat]") {
  for (float rho : {1.0f, 0.5f}) {
    const auto b = make_diffuse(constant_texture(Rgb::Constant(rho)));
    BsdfContext ctx;
    for (float ct : {1.0f, 0.5f, 0.05f}) {
      const Vec3 wi = test::dir_from(ct, 0.2f);
      const auto u = test::albedo_by_uniform(*b, ctx, wi, 200000, 77);
      INFO("rho " << rho << " cos " << ct << ": " << u.mean << " +- " << u.std_error);
      CHECK(std::abs(u.mean - double(rho)) <= 4.0 * u.std_error);
      const auto s = test::albedo_by_sampling(*b, ctx, wi, 1000, 78);
      CHECK(s.mean == Approx(double(rho)).epsilon(1e-6));  // cosine sampling: weight = albedo exactly
    }
  }
}

TEST_CASE("smooth dielectric: R + T = 1 and lobe probabilities follow Fresnel", "[stat]") {
  // T from the Fresnel transmission amplitudes (Born & Wolf 1.5.3, Eq. 21b):
  // T = (eta_t cos_t / (eta_i cos_i)) (t_s^2 + t_p^2) / 2, independent of R's formula.
  for (float eta : {1.5f, 1.33f, 2.4f})
    for (float ci : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f, -0.05f, -0.5f, -0.9f, -1.0f}) {
      const DielectricFresnel f = fresnel_dielectric(ci, eta);
      if (f.cos_t == 0.0f) {
        CHECK(f.reflectance == 1.0f);
        continue;
      }
      const double n = f.eta_ti, c1 = std::abs(double(ci)), c2 = std::abs(double(f.cos_t));
      const double ts = 2 * c1 / (c1 + n * c2), tp = 2 * c1 / (n * c1 + c2);
      const double t = n * c2 / c1 * 0.5 * (ts * ts + tp * tp);
      INFO("eta " << eta << " cos " << ci);
      CHECK(double(f.reflectance) + t == Approx(1.0).epsilon(1e-5));
      CHECK(f.cos_t * ci < 0.0f);
    }
  // Sampled lobe frequencies: binomial proportion within 4 standard errors.
  const auto glass = make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx);
  BsdfContext imp;
  imp.mode = TransportMode::importance;
  for (float ci : {0.9f, 0.3f, -0.6f}) {
    const Vec3 wi = test::dir_from(ci, 0.5f);
    const double fr = fresnel_dielectric(ci, 1.5f).reflectance;
    core::Rng rng(3, 1);
    const int n = 100000;
    int refl = 0, failed = 0;
    double total = 0;
    for (int k = 0; k < n; ++k) {
      const float ul = rng.uniform();
      const auto s = glass->sample(imp, wi, ul, rng.uniform2());
      if (!s) {
        ++failed;
        continue;
      }
      refl += s->lobe == kDeltaReflection;
      total += double(s->weight[0]);
    }
    CHECK(failed == 0);
    CHECK(std::abs(double(refl) / n - fr) <= 4.0 * std::sqrt(fr * (1 - fr) / n) + 1e-9);
    CHECK(total / n == Approx(1.0).epsilon(1e-6));  // R + T = 1 with unit specular factors
  }
}

namespace {
// Test-side broken BSDF: `inner` with eval() scaled by `eval_scale` and sample()
// weights by `weight_scale` (pdf unchanged).
class ScaledBsdf final : public Bsdf {
 public:
  ScaledBsdf(BsdfPtr inner, float eval_scale, float weight_scale)
      : m_inner(std::move(inner)), m_e(eval_scale), m_w(weight_scale) {}
  Rgb eval(const BsdfContext& c, const Vec3& wi, const Vec3& wo) const override { return m_e * m_inner->eval(c, wi, wo); }
  float pdf(const BsdfContext& c, const Vec3& wi, const Vec3& wo) const override { return m_inner->pdf(c, wi, wo); }
  std::optional<BsdfSample> sample(const BsdfContext& c, const Vec3& wi, float ul, const Vec2& u) const override {
    auto s = m_inner->sample(c, wi, ul, u);
    if (s) s->weight *= m_w;
    return s;
  }
  float roughness() const override { return m_inner->roughness(); }
  uint32_t lobes() const override { return m_inner->lobes(); }
  std::string name() const override { return "scaled"; }

 private:
  BsdfPtr m_inner;
  float m_e, m_w;
};
}  // namespace

TEST_CASE("energy tests reject a BSDF that gains 5 % energy", "[stat]") {
  // The same estimators, sample counts and acceptance rules as the two tests above.
  //  * albedo <= 1 (20k samples of sample() weights): a white diffuse BSDF has weight
  //    exactly rho = 1 (zero variance), so any gain > 1e-5 is caught; x1.05 is 5e-2.
  //    This test only sees gains that push the albedo over 1 + 4 se: a white GGX
  //    conductor (F = 1, alpha 0.3) measured albedo 0.87 / 0.81 at cos 0.9 / 0.4, and
  //    x1.05 (0.91 / 0.85) was watched passing it, as expected; the comparison below is
  //    the test that sees such an inconsistency when only eval() is wrong.
  //  * sample() vs uniform (50k + 200k samples): for diffuse rho 0.6 the uniform
  //    estimator's sd is sqrt(5/3) rho (4 rho cos on the upper half), se 1.7e-3, so
  //    4 se = 1.1 % relative: an eval() gaining 5 % while sample() weights stay true (the
  //    two disagree by 0.03) is ~17 se off. An energy gain applied consistently to eval
  //    and weights is invisible to this test by design; the albedo test catches it.
  const auto tex = [](float v) { return constant_texture(Rgb::Constant(v)); };
  BsdfContext ctx;
  ctx.mode = TransportMode::importance;
  uint64_t seed = 9000;
  for (const BsdfPtr& inner : {make_diffuse(tex(1.0f))})
    for (float ct : {0.9f, 0.4f}) {
      const Vec3 wi = test::dir_from(ct, 0.3f);
      const auto real = test::albedo_by_sampling(*inner, ctx, wi, 20000, seed);
      const auto gain = test::albedo_by_sampling(ScaledBsdf(inner, 1.05f, 1.05f), ctx, wi, 20000, seed++);
      INFO(inner->name() << " cos " << ct << ": real " << real.mean << " +- " << real.std_error << ", x1.05 "
                         << gain.mean << " +- " << gain.std_error);
      CHECK(albedo_at_most_one(real));
      CHECK_FALSE(albedo_at_most_one(gain));
      std::cout << "[bsdf energy power] " << inner->name() << " cos " << ct << ": real " << real.mean << " x1.05 "
                << gain.mean << " (" << (gain.mean - 1.0) / std::max(gain.std_error, 1e-12) << " se above 1)\n";
    }
  const auto diffuse = make_diffuse(tex(0.6f));
  for (float ct : {0.9f, 0.5f, 0.2f}) {
    const Vec3 wi = test::dir_from(ct, 0.3f);
    const ScaledBsdf eval_gain(diffuse, 1.05f, 1.0f);
    const auto s = test::albedo_by_sampling(*diffuse, ctx, wi, 50000, seed++);
    const auto u = test::albedo_by_uniform(*diffuse, ctx, wi, 200000, seed);
    const auto ub = test::albedo_by_uniform(eval_gain, ctx, wi, 200000, seed++);
    const auto sb = test::albedo_by_sampling(eval_gain, ctx, wi, 50000, seed++);
    INFO("cos " << ct << ": sampled " << s.mean << " uniform " << u.mean << " +- " << u.std_error << ", eval x1.05 "
                << ub.mean);
    CHECK(estimates_agree(s, u));
    CHECK_FALSE(estimates_agree(sb, ub));
    std::cout << "[bsdf energy power] eval x1.05 cos " << ct << ": |diff| " << std::abs(sb.mean - ub.mean) << " = "
              << std::abs(sb.mean - ub.mean) / std::sqrt(sqr(sb.std_error) + sqr(ub.std_error)) << " se\n";
  }
}
