// Emitter sampling: chi-square goodness of fit of sample_direct against pdf_direct
// (directions from a reference point), consistency of the returned pdf with
// pdf_direct, one-sidedness, power, and the analytic values of delta emitters.
#include <catch2/catch.hpp>

#include <functional>

#include "core/warp.h"
#include "tests/scene/geometry_test_util.h"
#include "tests/support/chi2.h"

using namespace dp;
using namespace dp::scene;

namespace {

constexpr int kChi2Tests = 11;  // chi-square tests in this file (Šidák family)

test::Chi2Options chi2_opts(uint64_t seed) {
  test::Chi2Options o;
  o.theta_bins = 20;
  o.phi_bins = 40;
  o.samples = 200000;
  o.test_count = kChi2Tests;
  o.seed = seed;
  return o;
}

test::DirectionSampler direct_sampler(const Emitter& e, const Vec3& ref) {
  return [&e, ref](core::Rng& rng) -> std::optional<Vec3> {
    const DirectSample s = e.sample_direct(ref, rng.uniform2());
    if (!(s.pdf > 0.0f)) return std::nullopt;
    return s.wi;
  };
}

test::Chi2Result area_chi2(const AreaEmitter& e, const Vec3& ref, uint64_t seed) {
  return test::chi2_sphere(direct_sampler(e, ref), [&](const Vec3& w) { return test::area_pdf_along(e, ref, w); },
                           chi2_opts(seed));
}

// The pdf returned with each sample equals pdf_direct at the sampled point, and a
// sample with pdf > 0 carries the emitter's radiance.
void check_sample_pdf_consistency(const AreaEmitter& e, const Vec3& ref) {
  core::Rng rng(11, 0);
  int valid = 0;
  for (int i = 0; i < 2000; ++i) {
    const DirectSample s = e.sample_direct(ref, rng.uniform2());
    if (!(s.pdf > 0.0f)) {
      REQUIRE(is_black(s.radiance));
      continue;
    }
    ++valid;
    REQUIRE(s.pdf == Approx(e.pdf_direct(ref, s.p, s.n, s.wi)).epsilon(1e-4));
    // pdf_area is the area density of the returned point: pdf * cos_l / d^2 (for
    // meshes, uniform area sampling: 1 / area).
    const float cos_l = -s.n.dot(s.wi);
    REQUIRE(s.pdf_area == Approx(s.pdf * cos_l / (s.dist * s.dist)).epsilon(1e-3));
    if (e.shape()->kind() == ShapeKind::mesh) REQUIRE(s.pdf_area == Approx(1.0f / e.shape()->area()).epsilon(1e-5));
    REQUIRE(s.dist == Approx((s.p - ref).norm()).epsilon(1e-5));
    REQUIRE((s.radiance == e.radiance()).all());
  }
  REQUIRE(valid > 0);
}

std::unique_ptr<TriangleMesh> ceiling_quad(float h) {
  // Normal (v1 - v0) x (v2 - v0) points down (-z), toward a reference below.
  return test::make_quad(Vec3(-1, -1, h), Vec3(-1, 1, h), Vec3(1, 1, h), Vec3(1, -1, h));
}

// Small lat-long map: a smooth gradient plus a bright 2x2 spot.
core::Image test_latlong() {
  core::Image img(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) img(x, y) = Rgb(0.2f + 0.05f * float(x % 7), 0.3f, 0.1f + 0.02f * float(y));
  for (int y = 5; y < 7; ++y)
    for (int x = 20; x < 22; ++x) img(x, y) = Rgb(200, 150, 100);
  return img;
}

Mat3 test_rotation() { return Eigen::AngleAxisf(0.7f, Vec3(0.3f, 1.0f, -0.4f).normalized()).toRotationMatrix(); }

}  // namespace

TEST_CASE("area emitter on a quad: sample_direct matches pdf_direct", "[stat]") {
  auto quad = ceiling_quad(0.4f);
  AreaEmitter e(quad.get(), Rgb(1, 2, 3));
  const Vec3 ref(0.3f, -0.2f, 0.0f);
  check_sample_pdf_consistency(e, ref);
  const auto r = area_chi2(e, ref, 1);
  INFO(r.report);
  CHECK(r.passed);
  CHECK(r.integral == Approx(1.0).epsilon(2e-3));
}

TEST_CASE("area emitter on a tilted triangle: sample_direct matches pdf_direct", "[stat]") {
  auto tri = test::make_mesh({Vec3(-1, 0.5f, 0.2f), Vec3(1.5f, -0.5f, 0.6f), Vec3(0.2f, 1.2f, 1.4f)}, {{0, 1, 2}});
  AreaEmitter e(tri.get(), Rgb(1, 1, 1));
  // Reference on the front side.
  const Vec3 centroid = (tri->positions[0] + tri->positions[1] + tri->positions[2]) / 3.0f;
  const Vec3 ng = (tri->positions[1] - tri->positions[0]).cross(tri->positions[2] - tri->positions[0]).normalized();
  const Vec3 ref = centroid + 0.5f * ng + Vec3(0.1f, -0.2f, 0.05f);
  check_sample_pdf_consistency(e, ref);
  const auto r = area_chi2(e, ref, 2);
  INFO(r.report);
  CHECK(r.passed);
}

using DirPdf = std::function<double(const Vec3& ref, const Vec3& w)>;

test::Chi2Result sphere_cone_chi2(const AreaEmitter& e, const Sphere& sphere, const Vec3& ref, const DirPdf& claimed,
                                  uint64_t seed) {
  const Frame f = Frame::from_normal((sphere.center() - ref).normalized());
  const double k = double((sphere.center() - ref).norm() / sphere.radius());
  const double one_minus_cos_max = 1.0 - std::sqrt(1.0 - 1.0 / sqr(k));
  const auto sampler = [&](core::Rng& rng) -> std::optional<Vec3> {
    const DirectSample s = e.sample_direct(ref, rng.uniform2());
    if (!(s.pdf > 0.0f)) return std::nullopt;
    const Vec3 l = f.to_local(s.wi);
    const double z = 1.0 - 2.0 * (1.0 - double(l.z())) / one_minus_cos_max;
    const double sin_old = std::sqrt(std::max(0.0, 1.0 - sqr(double(l.z()))));
    const double sin_new = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double scale = sin_old > 0 ? sin_new / sin_old : 0.0;
    return Vec3(float(double(l.x()) * scale), float(double(l.y()) * scale), float(z));
  };
  const auto pdf = [&](const Vec3& w) {
    const double cos_t = 1.0 - (1.0 - double(w.z())) * 0.5 * one_minus_cos_max;
    const double sin_new = std::sqrt(std::max(0.0, 1.0 - sqr(double(w.z()))));
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double scale = sin_new > 0 ? sin_t / sin_new : 0.0;
    const Vec3 wc = f.to_world(Vec3(float(double(w.x()) * scale), float(double(w.y()) * scale), float(cos_t))).normalized();
    return claimed(ref, wc) * 0.5 * one_minus_cos_max;
  };
  return test::chi2_sphere(sampler, pdf, chi2_opts(seed));
}

// The sphere seen from outside is sampled uniformly inside its cone, a pdf with a hard
// edge. The harness integrates expected counts by the midpoint rule, whose error on
// cells cut by that edge exceeds the sampling noise for small cones. So the test runs
// in an adapted domain (Mitsuba 3's chi-square "adapter" idea): directions in the cone
// (cos theta' in [cos_max, 1] about the axis) are stretched onto the whole sphere by
// z = 1 - 2 (1 - cos theta') / (1 - cos_max), phi unchanged, a map with constant
// Jacobian dω_sphere / dω_cone = 2 / (1 - cos_max). The claimed density becomes
// pdf_direct * (1 - cos_max) / 2 (1 / 4π if correct) with no edge left.
TEST_CASE("area emitter on a sphere: sample_direct matches pdf_direct, far and close", "[stat]") {
  Sphere sphere(Vec3(0.2f, -0.1f, 0.3f), 0.8f);
  AreaEmitter e(&sphere, Rgb(1, 1, 1));
  int seed = 3;
  for (const float k : {3.2f, 1.4f, 1.05f}) {  // distance to the center / radius
    const Vec3 ref = sphere.center() + Vec3(0.5f, -0.3f, 0.62f).normalized() * (k * sphere.radius());
    check_sample_pdf_consistency(e, ref);
    const auto r = sphere_cone_chi2(
        e, sphere, ref, [&](const Vec3& x, const Vec3& w) { return test::area_pdf_along(e, x, w); }, uint64_t(seed++));
    INFO("distance / radius " << k << "\n" << r.report);
    CHECK(r.passed);
    CHECK(r.sampled_fraction == 1.0);  // cone sampling: every sample hits the visible cap
    CHECK(r.integral == Approx(1.0).epsilon(2e-3));
    if (k < 1.1f) {  // a nearly hemispherical cap is fine without the adapter
      const auto direct = area_chi2(e, ref, uint64_t(seed++));
      INFO(direct.report);
      CHECK(direct.passed);
    }
  }
  // Seen from outside, an inward-facing sphere shows only back sides.
  sphere.flip_normals = true;
  core::Rng rng(5, 0);
  for (int i = 0; i < 100; ++i) {
    const DirectSample s = e.sample_direct(sphere.center() + Vec3(1, 1, 1), rng.uniform2());
    REQUIRE(s.pdf == 0.0f);
    REQUIRE(is_black(s.radiance));
  }
}

TEST_CASE("area emitter inside an inward-facing sphere: area sampling matches pdf_direct", "[stat]") {
  Sphere dome(Vec3(0.1f, 0.2f, -0.3f), 1.5f);
  dome.flip_normals = true;
  AreaEmitter e(&dome, Rgb(1, 1, 1));
  const Vec3 ref = dome.center() + Vec3(0.6f, -0.5f, 0.7f);
  check_sample_pdf_consistency(e, ref);
  const auto r = area_chi2(e, ref, 9);
  INFO(r.report);
  CHECK(r.passed);
  CHECK(r.sampled_fraction == 1.0);
  // Outward normals seen from inside: every sample is a back side.
  Sphere ball(Vec3(0, 0, 0), 1.0f);
  AreaEmitter eb(&ball, Rgb(1, 1, 1));
  core::Rng rng(6, 0);
  for (int i = 0; i < 100; ++i) REQUIRE(eb.sample_direct(Vec3(0.2f, 0.1f, 0.3f), rng.uniform2()).pdf == 0.0f);
}

TEST_CASE("environment map: sample_direct matches pdf_direct", "[stat]") {
  EnvironmentEmitter env(test_latlong(), test_rotation(), 1.5f);
  Bounds3 b;
  b.expand(Vec3(-1, -1, -1));
  b.expand(Vec3(1, 1, 1));
  env.prepare(b);
  const Vec3 ref(0.1f, 0.2f, 0.3f);
  const auto r = test::chi2_sphere(direct_sampler(env, ref),
                                   [&](const Vec3& w) { return double(env.pdf_direct(ref, Vec3::Zero(), Vec3::Zero(), w)); },
                                   chi2_opts(5));
  INFO(r.report);
  CHECK(r.passed);
  CHECK(r.integral == Approx(1.0).epsilon(2e-3));
  core::Rng rng(3, 0);
  for (int i = 0; i < 2000; ++i) {
    const DirectSample s = env.sample_direct(ref, rng.uniform2());
    if (!(s.pdf > 0.0f)) continue;
    REQUIRE(s.pdf == Approx(env.pdf_direct(ref, Vec3::Zero(), Vec3::Zero(), s.wi)).epsilon(1e-3));
    REQUIRE(((s.radiance - env.eval_direction(s.wi)).abs() < 1e-4f).all());
    REQUIRE(s.dist == kInfinity);
  }
}

TEST_CASE("constant environment: sample_direct matches pdf_direct", "[stat]") {
  EnvironmentEmitter env(Rgb(0.5f, 1, 2));
  const Vec3 ref(0, 0, 0);
  const auto r = test::chi2_sphere(direct_sampler(env, ref),
                                   [&](const Vec3& w) { return double(env.pdf_direct(ref, Vec3::Zero(), Vec3::Zero(), w)); },
                                   chi2_opts(6));
  INFO(r.report);
  CHECK(r.passed);
  CHECK(r.sampled_fraction == 1.0);
}

TEST_CASE("emitter chi-square rejects wrong pdfs", "[stat]") {
  // Area: dropping the cosine of the area-to-solid-angle Jacobian.
  auto quad = ceiling_quad(0.4f);
  AreaEmitter e(quad.get(), Rgb(1, 1, 1));
  const Vec3 ref(0.3f, -0.2f, 0.0f);
  auto bad_area = [&](const Vec3& w) {
    const auto h = test::intersect_mesh(*quad, ref, w);
    if (!h || h->ng.dot(w) >= 0) return 0.0;
    return double((h->p - ref).squaredNorm() / quad->area());
  };
  const auto r1 = test::chi2_sphere(direct_sampler(e, ref), bad_area, chi2_opts(7));
  CHECK_FALSE(r1.passed);
  // Sphere: the uniform-area density (a plausible mix-up of the two strategies),
  // rescaled to integrate to the same mass.
  Sphere sphere(Vec3(0, 0, 0), 1.0f);
  AreaEmitter es(&sphere, Rgb(1, 1, 1));
  const Vec3 sref(0.3f, 1.5f, -0.9f);
  const auto area_pdf = [&](const Vec3& x, const Vec3& w) {
    Ray ray{x, w};
    float t;
    if (!sphere.intersect(ray, t)) return 0.0;
    const Vec3 p = ray.at(t), n = p.normalized();
    return double(sqr(t) / (-n.dot(w) * sphere.area()));
  };
  const double mass = test::integrate_sphere([&](const Vec3& w) { return area_pdf(sref, w); }, 512, 1024);
  const auto r3 = sphere_cone_chi2(es, sphere, sref, [&](const Vec3& x, const Vec3& w) { return area_pdf(x, w) / mass; }, 10);
  CHECK_FALSE(r3.passed);
  // Environment: forgetting the sin(theta) of the lat-long Jacobian.
  EnvironmentEmitter env(test_latlong(), Mat3::Identity(), 1.0f);
  const auto r2 = test::chi2_sphere(
      direct_sampler(env, ref),
      [&](const Vec3& w) {
        const double p = double(env.pdf_direct(ref, Vec3::Zero(), Vec3::Zero(), w));
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - sqr(double(w.y()))));
        return p * sin_theta * 0.5 * kPiD;  // pdf_uv / (2 pi^2) * (pi / 2) keeps mass ~ 1
      },
      chi2_opts(8));
  CHECK_FALSE(r2.passed);
}

TEST_CASE("area emitters emit from the front side only", "[unit]") {
  auto quad = ceiling_quad(1.0f);  // normal -z
  AreaEmitter e(quad.get(), Rgb(2, 2, 2));
  SurfacePoint sp;
  sp.ng = Vec3(0, 0, -1);
  CHECK((e.eval(sp, Vec3(0, 0.6f, -0.8f)) == Rgb(2, 2, 2)).all());
  CHECK(is_black(e.eval(sp, Vec3(0, 0.6f, 0.8f))));
  // From above (behind the quad) every sample fails.
  core::Rng rng(1, 0);
  for (int i = 0; i < 100; ++i) {
    const DirectSample s = e.sample_direct(Vec3(0.2f, 0.1f, 2.0f), rng.uniform2());
    REQUIRE(s.pdf == 0.0f);
    REQUIRE(is_black(s.radiance));
    REQUIRE(e.pdf_direct(Vec3(0.2f, 0.1f, 2.0f), s.p, s.n, s.wi) == 0.0f);
  }
  // Power of a one-sided Lambertian emitter: pi * A * L.
  CHECK(e.power()[0] == Approx(kPi * 4.0f * 2.0f));
  Sphere sphere(Vec3(0, 0, 0), 0.5f);
  AreaEmitter es(&sphere, Rgb(1, 1, 1));
  CHECK(es.power()[1] == Approx(kPi * 4.0f * kPi * 0.25f));
  CHECK(e.kind() == EmitterKind::area);
  CHECK_FALSE(e.is_delta());
}

TEST_CASE("point light: radiance is intensity / d^2", "[unit]") {
  PointEmitter p(Vec3(1, 2, 3), Rgb(4, 8, 12));
  const Vec3 ref(1, 2, 0);
  const DirectSample s = p.sample_direct(ref, Vec2(0.3f, 0.7f));
  CHECK(s.delta);
  CHECK(s.pdf == 1.0f);
  CHECK(s.dist == Approx(3.0f));
  CHECK((s.wi - Vec3(0, 0, 1)).norm() < 1e-6f);
  CHECK(s.radiance[0] == Approx(4.0f / 9.0f));
  CHECK(s.radiance[2] == Approx(12.0f / 9.0f));
  CHECK(p.pdf_direct(ref, s.p, s.n, s.wi) == 0.0f);
  CHECK(p.power()[0] == Approx(4.0f * kPi * 4.0f));
  CHECK(p.is_delta());
}

TEST_CASE("spot light: smoothstep falloff between falloff_start and cutoff", "[unit]") {
  const float cutoff = 30, start = 20;
  SpotEmitter spot(Vec3(0, 0, 0), Vec3(0, 0, -2), Rgb(10, 10, 10), cutoff, start);
  auto at_angle = [](float deg) { return Vec3(std::sin(deg_to_rad(deg)), 0.0f, -std::cos(deg_to_rad(deg))); };
  CHECK(spot.intensity(at_angle(0))[0] == Approx(10.0f));
  CHECK(spot.intensity(at_angle(19.9f))[0] == Approx(10.0f));
  CHECK(spot.intensity(at_angle(30.1f))[0] == 0.0f);
  CHECK(spot.intensity(at_angle(90))[0] == 0.0f);
  for (const float deg : {21.0f, 25.0f, 29.0f}) {
    const double cc = std::cos(double(deg_to_rad(cutoff))), cs = std::cos(double(deg_to_rad(start)));
    const double x = (std::cos(double(deg_to_rad(deg))) - cc) / (cs - cc);
    CHECK(double(spot.intensity(at_angle(deg))[0]) == Approx(10.0 * x * x * (3.0 - 2.0 * x)).epsilon(1e-4));
  }
  // Radiance at a receiver 2 units away at 25 degrees = I(25 deg) / 4.
  const Vec3 ref = 2.0f * at_angle(25);
  const DirectSample s = spot.sample_direct(ref, Vec2(0.5f, 0.5f));
  CHECK(s.delta);
  CHECK(s.radiance[1] == Approx(spot.intensity(at_angle(25))[1] / 4.0f).epsilon(1e-4));
  // Power = integral of the intensity over the sphere (midpoint rule in cos theta).
  double integral = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double z = -1.0 + 2.0 * (i + 0.5) / n;
    const double s_t = std::sqrt(1.0 - z * z);
    integral += double(spot.intensity(Vec3(float(s_t), 0.0f, float(-z)))[0]) * 2.0 * kPiD * (2.0 / n);
  }
  CHECK(double(spot.power()[0]) == Approx(integral).epsilon(1e-3));
  // A hard-edged spot (falloff_start = cutoff).
  SpotEmitter hard(Vec3(0, 0, 0), Vec3(0, 0, -1), Rgb(1, 1, 1), 30, 30);
  CHECK(hard.intensity(at_angle(29.9f))[0] == 1.0f);
  CHECK(hard.intensity(at_angle(30.1f))[0] == 0.0f);
}

TEST_CASE("directional light: irradiance along minus the travel direction", "[unit]") {
  DirectionalEmitter d(Vec3(0, -2, 0), Rgb(3, 3, 3));
  Bounds3 b;
  b.expand(Vec3(-1, -1, -1));
  b.expand(Vec3(1, 1, 1));
  d.prepare(b);
  const DirectSample s = d.sample_direct(Vec3(0.5f, 0, 0), Vec2(0.1f, 0.9f));
  CHECK(s.delta);
  CHECK((s.wi - Vec3(0, 1, 0)).norm() < 1e-6f);
  CHECK(s.radiance[0] == 3.0f);
  CHECK(s.dist == kInfinity);
  CHECK(s.p.y() > std::sqrt(3.0f));  // outside the scene's bounding sphere
  CHECK(d.power()[0] == Approx(3.0f * kPi * 3.0f));
  CHECK(d.is_infinite());
}

TEST_CASE("environment map follows Mitsuba's lat-long parameterization", "[unit]") {
  // One distinct pixel per probe: u = 0.5 looks along +z, u = 0.25 along +x,
  // u = 0.75 along -x, u = 0 along -z; row 0 is +y.
  core::Image img(8, 4, Rgb(0, 0, 0));
  img(4, 1) = Rgb(1, 0, 0);  // u in [0.5, 0.625), just above the equator
  img(2, 2) = Rgb(0, 1, 0);  // u in [0.25, 0.375), just below
  img(6, 2) = Rgb(0, 0, 1);
  img(0, 0) = Rgb(5, 5, 5);
  EnvironmentEmitter env(img, Mat3::Identity(), 2.0f);
  auto dir = [](float u, float v) {
    const float phi = 2 * kPi * u, theta = kPi * v;
    return Vec3(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
  };
  CHECK((dir(0.5f, 0.5f) - Vec3(0, 0, 1)).norm() < 1e-6f);
  CHECK((dir(0.25f, 0.5f) - Vec3(1, 0, 0)).norm() < 1e-6f);
  CHECK((env.eval_direction(dir(0.56f, 0.4f)) == Rgb(2, 0, 0)).all());
  CHECK((env.eval_direction(dir(0.3f, 0.6f)) == Rgb(0, 2, 0)).all());
  CHECK((env.eval_direction(dir(0.8f, 0.6f)) == Rgb(0, 0, 2)).all());
  CHECK((env.eval_direction(dir(0.05f, 0.1f)) == Rgb(10, 10, 10)).all());
  // to_world rotates the map: rotating +z to +x moves the red pixel there.
  const Mat3 rot = Eigen::AngleAxisf(0.5f * kPi, Vec3(0, 1, 0)).toRotationMatrix();
  EnvironmentEmitter rotated(img, rot, 1.0f);
  const Vec3 w = rot * dir(0.56f, 0.4f);
  CHECK((rotated.eval_direction(w) == Rgb(1, 0, 0)).all());
  CHECK_THROWS(EnvironmentEmitter(img, 2.0f * Mat3::Identity(), 1.0f));
}

TEST_CASE("environment power is pi R^2 times the radiance integrated over directions", "[unit]") {
  Bounds3 b;
  b.expand(Vec3(0, 0, 0));
  b.expand(Vec3(2, 0, 0));  // radius 1
  EnvironmentEmitter c(Rgb(1, 1, 1));
  c.prepare(b);
  CHECK(c.power()[0] == Approx(4.0f * kPi * kPi));
  EnvironmentEmitter m(core::Image(16, 8, Rgb(0.5f, 0.5f, 0.5f)), Mat3::Identity(), 2.0f);
  m.prepare(b);
  CHECK(m.power()[0] == Approx(4.0f * kPi * kPi).epsilon(1e-4));
}
