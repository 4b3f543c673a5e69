// Unit tests of the Fresnel and microfacet building blocks.
#include <catch2/catch.hpp>

#include "scene/bsdf/fresnel.h"
#include "scene/bsdf/microfacet.h"
#include "scene/bsdf/rough_transmittance.h"
#include "tests/scene/bsdf_chi2_adapter.h"
#include "tests/scene/bsdf_test_cases.h"

using namespace dp;
using namespace dp::scene;

TEST_CASE("dielectric Fresnel: known values and total internal reflection", "[unit]") {
  CHECK(fresnel_dielectric(1.0f, 1.5f).reflectance == Approx(0.04f).epsilon(1e-5));  // ((n-1)/(n+1))^2
  CHECK(fresnel_dielectric(-1.0f, 1.5f).reflectance == Approx(0.04f).epsilon(1e-5));
  CHECK(fresnel_dielectric(0.0f, 1.5f).reflectance == Approx(1.0f));
  // Critical angle from inside: sin = 1/1.5.
  const float cc = std::sqrt(1.0f - 1.0f / 2.25f);
  CHECK(fresnel_dielectric(-(cc - 1e-3f), 1.5f).reflectance == 1.0f);
  CHECK(fresnel_dielectric(-(cc + 1e-3f), 1.5f).reflectance < 1.0f);
  CHECK(fresnel_dielectric(0.7f, 1.0f).reflectance == 0.0f);
  // Brewster angle: tan = n, R = R_s / 2 only (R_p = 0).
  const float cb = std::cos(std::atan(1.5f));
  const float sb = std::sin(std::atan(1.5f)), st = sb / 1.5f, ct = std::sqrt(1 - st * st);
  const float rs = (cb - 1.5f * ct) / (cb + 1.5f * ct);
  CHECK(fresnel_dielectric(cb, 1.5f).reflectance == Approx(0.5f * rs * rs).epsilon(1e-4));
}

TEST_CASE("conductor Fresnel: k = 0 reduces to the dielectric, Schlick end points", "[unit]") {
  for (float c : {1.0f, 0.7f, 0.3f, 0.05f}) {
    const Rgb f = fresnel_conductor(c, Rgb(1.5f, 2.0f, 1.2f), Rgb::Zero());
    CHECK(f[0] == Approx(fresnel_dielectric(c, 1.5f).reflectance).epsilon(1e-5));
    CHECK(f[1] == Approx(fresnel_dielectric(c, 2.0f).reflectance).epsilon(1e-5));
    CHECK(f[2] == Approx(fresnel_dielectric(c, 1.2f).reflectance).epsilon(1e-5));
  }
  // Normal incidence: |(n - 1) / (n + 1)|^2 with complex n = 0.2 + 3i.
  const float expect = (sqr(0.2f - 1) + 9) / (sqr(0.2f + 1) + 9);
  CHECK(fresnel_conductor(1.0f, Rgb::Constant(0.2f), Rgb::Constant(3.0f))[0] == Approx(expect).epsilon(1e-5));
  CHECK(fresnel_conductor(0.0f, Rgb::Constant(0.2f), Rgb::Constant(3.0f))[0] == Approx(1.0f));
  CHECK(fresnel_schlick(1.0f, 0.3f) == Approx(0.3f));
  CHECK(fresnel_schlick(0.0f, 0.3f) == Approx(1.0f));
}

TEST_CASE("diffuse Fresnel reflectance satisfies the reciprocity identity", "[unit]") {
  // Radiance reciprocity across the interface: 1 - Fdr(1/eta) = (1 - Fdr(eta)) / eta^2.
  for (float eta : {1.33f, 1.5f, 2.0f}) {
    const float ext = fresnel_diffuse_reflectance(eta), intr = fresnel_diffuse_reflectance(1.0f / eta);
    CHECK(1.0f - intr == Approx((1.0f - ext) / (eta * eta)).epsilon(1e-4));
  }
  CHECK(fresnel_diffuse_reflectance(1.5f) == Approx(0.0918f).epsilon(3e-3));  // tabulated Fdr(1.5)
}

namespace {
// \int over the sphere of f, by the midpoint rule after the equator warp of the
// chi-square adapter (which resolves lobes at the pole).
double integrate(const std::function<double(const Vec3&)>& f, const Vec3& axis_dir, int res) {
  const test::DirectionWarp warp(axis_dir);
  return test::integrate_sphere(
      [&](const Vec3& v) {
        double jac = 0;
        const Vec3 w = warp.inverse(v, jac);
        return f(w) * jac;
      },
      res, 2 * res);
}
}  // namespace

TEST_CASE("microfacet D is normalized and the visible normals integrate to 1", "[unit]") {
  // Quadrature tolerance: the midpoint rule at 512 x 1024 on these smooth integrands
  // is accurate to well below 1e-3 (checked against the 256 x 512 result below).
  for (MicrofacetType t : {MicrofacetType::beckmann, MicrofacetType::ggx})
    for (const Vec2& a : {Vec2(0.1f, 0.1f), Vec2(0.4f, 0.4f), Vec2(1.0f, 1.0f), Vec2(0.2f, 0.7f)}) {
      const Microfacet d(t, a.x(), a.y());
      const auto dcos = [&](const Vec3& m) { return double(d.D(m) * std::max(0.0f, m.z())); };
      const double i1 = integrate(dcos, Vec3(0, 0, 1), 512), i0 = integrate(dcos, Vec3(0, 0, 1), 256);
      INFO("type " << int(t) << " alpha " << a.transpose() << ": " << i1 << " (" << i0 << ")");
      CHECK(std::abs(i1 - i0) < 2e-3);
      // GGX tails: the fraction of \int D cos beyond the grid is ~ 0; Beckmann exact.
      CHECK(i1 == Approx(1.0).epsilon(2e-3));
      for (float ct : {0.95f, 0.5f, 0.1f}) {
        const Vec3 wi = test::dir_from(ct, 0.4f);
        const double v = integrate([&](const Vec3& m) { return double(d.pdf_visible(wi, m)); }, wi, 256);
        INFO("visible normals, cos " << ct << ": " << v);
        CHECK(v == Approx(1.0).epsilon(3e-3));  // Heitz 2014, Eq. 18 (tests Lambda / G1)
      }
    }
}

TEST_CASE("rough transmittance: approaches smooth Fresnel and conserves energy", "[unit]") {
  // alpha -> 0: T(mu) -> 1 - F(mu) (smooth interface).
  const Microfacet smooth(MicrofacetType::beckmann, 0.002f);
  for (float mu : {1.0f, 0.6f, 0.3f}) {
    const float t = RoughTransmittance::compute(smooth, 1.5f, mu, 16);
    CHECK(t == Approx(1.0f - fresnel_dielectric(mu, 1.5f).reflectance).epsilon(2e-3));
  }
  // Rough: T <= 1 - (reflected energy) is checked by the BSDF energy tests; here the
  // table interpolation matches direct quadrature at the node midpoints.
  const RoughTransmittance tab(MicrofacetType::ggx, 0.4f, 1.5f);
  const Microfacet d(MicrofacetType::ggx, 0.4f);
  for (float mu : {0.9f, 0.5f, 0.2f}) CHECK(tab.eval(mu) == Approx(RoughTransmittance::compute(d, 1.5f, mu, 48)).epsilon(5e-3));
  CHECK(tab.diffuse() > 0.0f);
  CHECK(tab.diffuse() < 1.0f);
}
