// Perspective camera: raster round trip, field of view at the image edges, orientation
// (row 0 = top), and the primary-direction pdf (normalization and Jacobian).
#include <catch2/catch.hpp>

#include "scene/camera.h"
#include "core/rng.h"
#include "tests/support/chi2.h"

using namespace dp;
using namespace dp::scene;

namespace {

CameraDesc test_desc(bool fov_x) {
  CameraDesc d;
  d.position = Vec3(1, 2, 3);
  d.look_at = Vec3(1.5f, 1.8f, 0);
  d.up = Vec3(0, 1, 0);
  d.fov_deg = 50;
  d.fov_axis_x = fov_x;
  d.width = 64;
  d.height = 40;
  return d;
}

float angle_deg(const Vec3& a, const Vec3& b) {
  return float(std::acos(std::clamp(double(a.normalized().dot(b.normalized())), -1.0, 1.0)) * 180.0 / kPiD);
}

}  // namespace

TEST_CASE("camera: raster_of inverts generate_ray", "[unit]") {
  for (const bool fov_x : {false, true}) {
    PerspectiveCamera cam(test_desc(fov_x));
    core::Rng rng(1, 0);
    for (int i = 0; i < 1000; ++i) {
      const Vec2 r(rng.uniform() * 64.0f, rng.uniform() * 40.0f);
      const Ray ray = cam.generate_ray(r);
      REQUIRE(std::abs(ray.d.norm() - 1.0f) < 1e-5f);
      const auto back = cam.raster_of(ray.at(0.1f + 10.0f * rng.uniform()));
      REQUIRE(back);
      REQUIRE((*back - r).norm() < 2e-3f);
    }
    // Behind the camera and outside the image: no raster position.
    CHECK_FALSE(cam.raster_of(cam.position() - cam.forward()));
    CHECK_FALSE(cam.raster_of(cam.generate_ray(Vec2(-1, 20)).at(1.0f)));
    CHECK_FALSE(cam.raster_of(cam.generate_ray(Vec2(30, 41)).at(1.0f)));
  }
}

TEST_CASE("camera: edge rays span the field of view; row 0 is the top", "[unit]") {
  const CameraDesc d = test_desc(false);
  PerspectiveCamera cam(d);
  const Vec3 fwd = (d.look_at - d.position).normalized();
  CHECK((cam.forward() - fwd).norm() < 1e-6f);
  const Ray center = cam.generate_ray(Vec2(32, 20));
  CHECK((center.d - fwd).norm() < 1e-6f);
  // fov along y: top-center and bottom-center rays are fov/2 from the axis.
  const Ray top = cam.generate_ray(Vec2(32, 0)), bottom = cam.generate_ray(Vec2(32, 40));
  CHECK(angle_deg(top.d, fwd) == Approx(25.0f).epsilon(1e-4));
  CHECK(angle_deg(bottom.d, fwd) == Approx(25.0f).epsilon(1e-4));
  CHECK(top.d.y() > bottom.d.y());  // row 0 looks up
  // x extent from the aspect ratio; column 0 looks left (right = forward x up).
  const Ray left = cam.generate_ray(Vec2(0, 20)), right = cam.generate_ray(Vec2(64, 20));
  const float half_x = float(std::atan(std::tan(25.0 * kPiD / 180.0) * 64.0 / 40.0) * 180.0 / kPiD);
  CHECK(angle_deg(left.d, fwd) == Approx(half_x).epsilon(1e-4));
  const Vec3 right_axis = fwd.cross(d.up).normalized();
  CHECK(right.d.dot(right_axis) > 0);
  CHECK(left.d.dot(right_axis) < 0);
  // Corner: tan components add in the image plane.
  const Ray corner = cam.generate_ray(Vec2(0, 0));
  const double tx = std::tan(double(half_x) * kPiD / 180.0), ty = std::tan(25.0 * kPiD / 180.0);
  CHECK(double(corner.d.dot(fwd)) == Approx(1.0 / std::sqrt(1.0 + tx * tx + ty * ty)).epsilon(1e-5));
  // fov along x.
  PerspectiveCamera camx(test_desc(true));
  CHECK(angle_deg(camx.generate_ray(Vec2(0, 20)).d, fwd) == Approx(25.0f).epsilon(1e-4));
  CHECK(angle_deg(camx.generate_ray(Vec2(64, 20)).d, fwd) == Approx(25.0f).epsilon(1e-4));
}

TEST_CASE("camera: invalid descriptions are rejected", "[unit]") {
  CameraDesc d = test_desc(false);
  d.look_at = d.position;
  CHECK_THROWS(PerspectiveCamera(d));
  d = test_desc(false);
  d.up = d.look_at - d.position;
  CHECK_THROWS(PerspectiveCamera(d));
  d = test_desc(false);
  d.fov_deg = 180;
  CHECK_THROWS(PerspectiveCamera(d));
  d = test_desc(false);
  d.width = 0;
  CHECK_THROWS(PerspectiveCamera(d));
}

TEST_CASE("camera: pdf_direction integrates to one over the image", "[unit]") {
  // Looking down +z so the image is a cap around the integration grid's pole.
  CameraDesc d = test_desc(false);
  d.position = Vec3(0, 0, 0);
  d.look_at = Vec3(0, 0, 1);
  d.fov_deg = 70;
  PerspectiveCamera cam(d);
  const auto pdf = [&](const Vec3& w) { return double(cam.pdf_direction(w)); };
  CHECK(test::integrate_sphere(pdf, 1024, 2048) == Approx(1.0).epsilon(3e-3));
  CHECK(cam.pdf_direction(Vec3(0, 0, -1)) == 0.0f);
  CHECK(cam.pdf_direction(Vec3(0, 0.99f, 0.14f).normalized()) == 0.0f);  // outside the fov
}

// Jacobian check (central finite differences): for uniform raster positions the
// density of the ray direction is 1 / (W H |dw/dx x dw/dy|), the raster-to-solid-angle
// Jacobian; pdf_direction must equal it everywhere on the image.
TEST_CASE("camera: pdf_direction equals the raster-to-direction Jacobian", "[unit]") {
  for (const bool fov_x : {false, true}) {
    PerspectiveCamera cam(test_desc(fov_x));
    core::Rng rng(7, 0);
    const double h = 1e-2;
    auto dir = [&](double x, double y) {
      const Vec3 d = cam.generate_ray(Vec2(float(x), float(y))).d;
      return Vec3d(double(d.x()), double(d.y()), double(d.z()));
    };
    auto jacobian_pdf = [&](double x, double y) {
      const Vec3d dx = (dir(x + h, y) - dir(x - h, y)) / (2 * h), dy = (dir(x, y + h) - dir(x, y - h)) / (2 * h);
      return 1.0 / (64.0 * 40.0 * dx.cross(dy).norm());
    };
    int wrong_rejected = 0;
    for (int i = 0; i < 200; ++i) {
      const double x = 1 + 62 * double(rng.uniform()), y = 1 + 38 * double(rng.uniform());
      const Vec3 w = cam.generate_ray(Vec2(float(x), float(y))).d;
      const double expected = jacobian_pdf(x, y);
      REQUIRE(double(cam.pdf_direction(w)) == Approx(expected).epsilon(2e-3));
      // A cos^2 Jacobian (a plausible bug) differs by the factor cos theta.
      const double c = double(w.dot(cam.forward()));
      if (std::abs(double(cam.pdf_direction(w)) * c - expected) > 2e-3 * expected) ++wrong_rejected;
    }
    CHECK(wrong_rejected > 190);
  }
}
