// Monte Carlo irradiance from Emitter::sample_direct against closed forms:
//   E(x, n) = integral of L(w) max(0, n . w) dw,  estimator L cos / pdf (0 if pdf = 0).
// Accepted within 4 standard errors; each test also shows that a 2% bias would be
// rejected (the standard error is small enough for the test to fail).
#include <catch2/catch.hpp>

#include "tests/scene/geometry_test_util.h"

using namespace dp;
using namespace dp::scene;

namespace {

constexpr int kSamples = 400000;

test::MeanEstimate mc_irradiance(const Emitter& e, const Vec3& x, const Vec3& n, uint64_t seed) {
  return test::mc_mean(
      [&](core::Rng& rng) {
        const DirectSample s = e.sample_direct(x, rng.uniform2());
        if (!(s.pdf > 0.0f)) return 0.0;
        return double(s.radiance[0]) * std::max(0.0, double(n.dot(s.wi))) / double(s.pdf);
      },
      kSamples, seed);
}

void check_estimate(const test::MeanEstimate& m, double exact) {
  INFO("MC " << m.mean << " +- " << m.std_error << ", exact " << exact);
  CHECK(std::abs(m.mean - exact) < 4.0 * m.std_error);
  // Power: a 2% error would be outside 4 standard errors.
  CHECK(0.02 * exact > 4.0 * m.std_error);
}

// Lambert's formula for the irradiance from a uniform polygon fully above the
// horizon of (x, n): E = L/2 * |sum_i Theta_i (n . gamma_i)|, Theta_i the angle the
// edge (v_i, v_i+1) subtends at x, gamma_i the unit normal of the plane through x and
// the edge (Arvo 1995, "Analytic methods for simulated light transport", Eq. 3.1).
double polygon_irradiance(const std::vector<Vec3>& poly, const Vec3& x, const Vec3& n, double radiance) {
  double sum = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3d a = (poly[i] - x).cast<double>().normalized();
    const Vec3d b = (poly[(i + 1) % poly.size()] - x).cast<double>().normalized();
    const double theta = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    sum += theta * n.cast<double>().dot(a.cross(b).normalized());
  }
  return 0.5 * radiance * std::abs(sum);
}

}  // namespace

TEST_CASE("irradiance from a quad light matches Lambert's formula", "[stat]") {
  const std::vector<Vec3> v{Vec3(-1, -0.5f, 1), Vec3(-1, 1.5f, 1), Vec3(0.5f, 1.5f, 1), Vec3(0.5f, -0.5f, 1)};
  auto quad = test::make_quad(v[0], v[1], v[2], v[3]);
  AreaEmitter e(quad.get(), Rgb(3, 3, 3));
  const Vec3 x(0.1f, 0.2f, 0.0f);
  for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0.3f, -0.2f, 1).normalized()}) {
    const double exact = polygon_irradiance(v, x, n, 3.0);
    check_estimate(mc_irradiance(e, x, n, 1), exact);
  }
  // A centered square of half-side a at height h: E = 4 L [a/sqrt(a^2+h^2) atan(a/sqrt(a^2+h^2))]
  // (the classic closed form; checks the Lambert helper itself).
  const double a = 1.0, h = 1.0, s = a / std::sqrt(a * a + h * h);
  const std::vector<Vec3> sq{Vec3(-1, -1, 1), Vec3(-1, 1, 1), Vec3(1, 1, 1), Vec3(1, -1, 1)};
  CHECK(polygon_irradiance(sq, Vec3(0, 0, 0), Vec3(0, 0, 1), 1.0) == Approx(4.0 * s * std::atan(s)));
}

TEST_CASE("irradiance from a triangle light matches Lambert's formula", "[stat]") {
  const std::vector<Vec3> v{Vec3(-0.5f, -0.4f, 0.8f), Vec3(0.2f, 1.0f, 1.3f), Vec3(0.9f, -0.3f, 0.6f)};
  auto tri = test::make_mesh(v, {{0, 1, 2}});
  AreaEmitter e(tri.get(), Rgb(2, 2, 2));
  const Vec3 x(0, 0, 0), n(0, 0, 1);
  REQUIRE(tri->area() > 0);
  // The triangle must face x (its normal points down).
  REQUIRE((v[1] - v[0]).cross(v[2] - v[0]).z() < 0);
  check_estimate(mc_irradiance(e, x, n, 2), polygon_irradiance(v, x, n, 2.0));
}

TEST_CASE("irradiance from a sphere light is pi L sin^2(alpha)", "[stat]") {
  const float r = 0.5f;
  Sphere sphere(Vec3(0.3f, -0.2f, 1.0f), r);
  AreaEmitter e(&sphere, Rgb(5, 5, 5));
  const Vec3 x(0.3f, -0.2f, 0.0f);
  uint64_t seed = 3;
  // Far (d = 2r) and close (d = 1.05 r), normal pointing at the center.
  for (const float d : {1.0f, 0.525f}) {
    const Vec3 xd = sphere.center() - Vec3(0, 0, d);
    const double sin2 = sqr(double(r) / double(d));
    check_estimate(mc_irradiance(e, xd, Vec3(0, 0, 1), seed++), kPiD * 5.0 * sin2);
  }
  (void)x;
  // Inward-facing sphere (flip_normals) lit from inside: a receiver at the center
  // facing any way sees L over a hemisphere, E = pi L.
  Sphere dome(Vec3(0, 0, 0), 2.0f);
  dome.flip_normals = true;
  AreaEmitter ed(&dome, Rgb(1.5f, 1.5f, 1.5f));
  check_estimate(mc_irradiance(ed, Vec3(0.3f, 0.1f, -0.4f), Vec3(0, 1, 0), 9), kPiD * 1.5);
}

TEST_CASE("constant environment irradiance is pi L", "[stat]") {
  EnvironmentEmitter env(Rgb(0.7f, 0.7f, 0.7f));
  check_estimate(mc_irradiance(env, Vec3(0, 0, 0), Vec3(0.6f, 0, 0.8f), 4), kPiD * 0.7);
}

TEST_CASE("environment map irradiance matches the per-pixel closed form", "[stat]") {
  // Upward normal (+y) in map space: E = sum over pixels above the horizon of
  // L_ij * dphi * (sin^2 theta1 - sin^2 theta0) / 2 (integral of cos sin dtheta dphi).
  const int w = 24, h = 12;  // even height: no row straddles the horizon
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img(x, y) = Rgb(0.1f + 0.03f * float((x * 5 + y * 3) % 11), 0, 0);
  img(7, 3) = Rgb(300, 0, 0);  // a sun
  double exact = 0;
  for (int y = 0; y < h / 2; ++y) {
    const double t0 = kPiD * y / h, t1 = kPiD * (y + 1) / h;
    for (int x = 0; x < w; ++x)
      exact += double(img(x, y)[0]) * (2 * kPiD / w) * 0.5 * (sqr(std::sin(t1)) - sqr(std::sin(t0)));
  }
  const Mat3 rot = Eigen::AngleAxisf(1.1f, Vec3(1, 0.2f, 0.5f).normalized()).toRotationMatrix();
  EnvironmentEmitter env(img, rot, 1.0f);
  check_estimate(mc_irradiance(env, Vec3(0, 0, 0), rot * Vec3(0, 1, 0), 5), exact);
}
