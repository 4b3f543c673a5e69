// Energy tests: directional albedo <= 1 (within 4 standard errors) for every BSDF and
// many incident directions; albedo from sample() weights equals an independent
// uniform-direction estimate of \int f |cos| (within 4 combined standard errors);
// white furnace of the diffuse BSDF; smooth dielectric R + T = 1.
// Dielectrics are tested in importance mode (physical energy); in radiance mode the
// 1/eta^2 factor legitimately exceeds 1 when leaving the denser medium.
#include <catch2/catch.hpp>
#include <iostream>

#include "scene/fresnel.h"
#include "tests/scene/bsdf_test_cases.h"

using namespace dp;
using namespace dp::scene;

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
      CHECK(a.mean <= 1.0 + 4.0 * a.std_error + 1e-5);
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
        const double se = std::sqrt(sqr(s.std_error) + sqr(u.std_error));
        INFO(name << " cos " << ct << " mode " << int(mode) << ": sampled " << s.mean << " +- " << s.std_error
                  << ", uniform " << u.mean << " +- " << u.std_error);
        CHECK(std::abs(s.mean - u.mean) <= 4.0 * se + 1e-6);
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
