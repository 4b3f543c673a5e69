// G-Plane's shift (Gruson et al. 2018, Sec. 5.3; gradients/volume_plane_shift.h), in
// double, on random configurations (a photon plane's light segment, a base and an offset
// camera ray as a pinhole's neighbouring pixels make them):
//  * the whole map w1 -> w1' at a fixed raster (plane x base ray -> w; d' = c' + w d';
//    rotation about the light segment) against central differences in spherical
//    coordinates: |dw1'/dw1| = |det'| / |det| t1 / t1' (rel <= 1e-4); Eq. 18's printed
//    t-factors (PlaneShiftFault::paper_eq18) are rejected by the same comparison;
//  * the offset plane holds d', keeps the angle to w0 and a0's segment, the offset ray
//    meets it at w' = w, and shifting back from the offset returns the base (bijection);
//  * the plane-ray solve against the point it returns.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "gradients/volume_plane_shift.h"

using namespace dp;
using V = Eigen::Vector3d;
using gradients::PlaneRotation;
using gradients::PlaneShiftFault;

namespace {

V random_unit(core::Rng& rng) {
  for (;;) {
    const V v(2.0 * rng.uniform_double() - 1.0, 2.0 * rng.uniform_double() - 1.0, 2.0 * rng.uniform_double() - 1.0);
    const double n = v.norm();
    if (n > 0.1 && n <= 1.0) return v / n;
  }
}

struct Config {
  V a0, w0, c, d, c_off, d_off;
};

// The base and offset camera rays of a pinhole through neighbouring pixels: one origin,
// directions ~1/256 rad apart; the light segment anywhere in a unit-size scene.
Config random_config(core::Rng& rng) {
  Config k;
  k.a0 = V(rng.uniform_double(), rng.uniform_double(), rng.uniform_double()) * 2.0 - V(1, 1, 1);
  k.w0 = random_unit(rng);
  k.c = V(0, 0, -3) + 0.2 * V(rng.uniform_double(), rng.uniform_double(), rng.uniform_double());
  k.d = (V(0, 0, 1) + 0.3 * random_unit(rng)).normalized();
  k.c_off = k.c;
  k.d_off = (k.d + random_unit(rng) / 256.0).normalized();
  return k;
}

// The shift at a fixed raster: w1 -> (w1', t0', t1') through w; false if it fails.
bool shift(const Config& k, const V& w1, double& t0, double& t1, double& w, PlaneRotation<double>& out) {
  double inv_det = 0;
  if (!gradients::plane_ray_solve(k.a0, k.w0, w1, k.c, k.d, t0, t1, w, inv_det)) return false;
  return gradients::rotate_plane_to(k.a0, k.w0, w1, V(k.c_off + w * k.d_off), out);
}

// Spherical coordinates about a polar axis e (with a fixed orthonormal frame).
struct Frame {
  V e, x, y;
  explicit Frame(const V& axis) : e(axis) {
    x = (std::abs(e.x()) < 0.9 ? V(1, 0, 0) : V(0, 1, 0)).cross(e).normalized();
    y = e.cross(x);
  }
  V dir(double th, double ph) const { return std::sin(th) * (std::cos(ph) * x + std::sin(ph) * y) + std::cos(th) * e; }
  void angles(const V& v, double& th, double& ph) const {
    th = std::acos(std::clamp(v.dot(e), -1.0, 1.0));
    ph = std::atan2(v.dot(y), v.dot(x));
  }
};

// Central differences of the map in (theta, phi) about a polar axis perpendicular to w1
// (both w1 and w1' near the equator): |dw1'/dw1| = |d(th', ph') / d(th, ph)| sin th' / sin th.
bool fd_jacobian(const Config& k, const V& w1, double& jac) {
  const Frame f(w1.cross(k.w0).normalized());
  double th = 0, ph = 0;
  f.angles(w1, th, ph);
  const double h = 1e-6;
  double out[4][2];
  const double dth[4] = {h, -h, 0, 0}, dph[4] = {0, 0, h, -h};
  for (int i = 0; i < 4; ++i) {
    double t0, t1, w;
    PlaneRotation<double> r;
    if (!shift(k, f.dir(th + dth[i], ph + dph[i]), t0, t1, w, r)) return false;
    f.angles(r.w1, out[i][0], out[i][1]);
  }
  auto wrap = [](double a) { return std::remainder(a, 2.0 * M_PI); };
  const double a = (out[0][0] - out[1][0]) / (2 * h), b = (out[2][0] - out[3][0]) / (2 * h);
  const double c = wrap(out[0][1] - out[1][1]) / (2 * h), d = wrap(out[2][1] - out[3][1]) / (2 * h);
  double t0, t1, w;
  PlaneRotation<double> r;
  if (!shift(k, w1, t0, t1, w, r)) return false;
  double th_off = 0, ph_off = 0;
  f.angles(r.w1, th_off, ph_off);
  jac = std::abs(a * d - b * c) * std::sin(th_off) / std::sin(th);
  return true;
}

// A base configuration the plane estimate can find: a1 on the segment (t0 in (0.05, 2)),
// the gather point on the camera ray (w in (1, 5)), w1 from a1 to it.
bool random_base(core::Rng& rng, const Config& k, V& w1) {
  const V a1 = k.a0 + (0.05 + 1.95 * rng.uniform_double()) * k.w0;
  const V x = k.c + (1.0 + 4.0 * rng.uniform_double()) * k.d;
  w1 = (x - a1).normalized();
  return (x - a1).norm() > 0.05 && std::abs(w1.dot(k.w0)) < 0.98;
}

struct JacobianRun {
  int tested = 0, failed_shift = 0;
  double worst = 0;  // max relative error against central differences
};

JacobianRun compare_jacobians(PlaneShiftFault fault) {
  core::Rng rng(7, 1);
  JacobianRun run;
  while (run.tested < 400) {
    const Config k = random_config(rng);
    V w1;
    if (!random_base(rng, k, w1)) continue;
    double t0, t1, w;
    PlaneRotation<double> r;
    if (!shift(k, w1, t0, t1, w, r) || !(r.t0 > 0.01)) {
      ++run.failed_shift;
      continue;
    }
    double fd = 0;
    if (!fd_jacobian(k, w1, fd)) continue;
    const double jac =
        gradients::plane_shift_jacobian(k.w0, w1, k.d, t0, t1, r.w1, V(k.d_off), r.t0, r.t1, fault);
    run.worst = std::max(run.worst, std::abs(jac / fd - 1.0));
    ++run.tested;
  }
  return run;
}

}  // namespace

TEST_CASE("plane shift: the Jacobian matches central differences", "[unit]") {
  const JacobianRun run = compare_jacobians(PlaneShiftFault::none);
  std::printf("plane shift Jacobian: %d configurations (%d failed shifts), worst rel error %.2e\n", run.tested,
              run.failed_shift, run.worst);
  CHECK(run.worst <= 1e-4);
}

TEST_CASE("plane shift: Eq. 18's printed t-factors are rejected by the same comparison", "[unit]") {
  const JacobianRun run = compare_jacobians(PlaneShiftFault::paper_eq18);
  std::printf("plane shift Jacobian with Eq. 18's t0'/t0 t1'/t1: worst rel error %.2e\n", run.worst);
  CHECK(run.worst > 1e-4);
}

TEST_CASE("plane shift: the offset plane holds d', keeps theta, and shifts back to the base", "[unit]") {
  core::Rng rng(11, 3);
  int tested = 0;
  while (tested < 1000) {
    const Config k = random_config(rng);
    V w1;
    if (!random_base(rng, k, w1)) continue;
    double t0, t1, w;
    PlaneRotation<double> r;
    if (!shift(k, w1, t0, t1, w, r)) continue;
    ++tested;
    const V d_off = k.c_off + w * k.d_off;
    CHECK((k.a0 + r.t0 * k.w0 + r.t1 * r.w1 - d_off).norm() < 1e-9);
    CHECK(std::abs(r.w1.norm() - 1.0) < 1e-12);
    CHECK(std::abs(r.w1.dot(k.w0) - w1.dot(k.w0)) < 1e-12);
    CHECK(r.t1 > 0.0);
    // The offset ray meets the offset plane at w' = w, with the same (t0', t1').
    double s0, s1, sw, inv;
    REQUIRE(gradients::plane_ray_solve(k.a0, k.w0, r.w1, k.c_off, k.d_off, s0, s1, sw, inv));
    CHECK(std::abs(sw - w) < 1e-9 * (1.0 + w));
    CHECK(std::abs(s0 - r.t0) < 1e-8);
    CHECK(std::abs(s1 - r.t1) < 1e-8);
    // The inverse: the same rotation from the offset back to the base ray.
    PlaneRotation<double> back;
    REQUIRE(gradients::rotate_plane_to(k.a0, k.w0, r.w1, V(k.c + sw * k.d), back));
    CHECK((back.w1 - w1).norm() < 1e-9);
    CHECK(std::abs(back.t0 - t0) < 1e-8);
    CHECK(std::abs(back.t1 - t1) < 1e-8);
  }
}

TEST_CASE("plane shift: the plane-ray solve returns the intersection", "[unit]") {
  core::Rng rng(5, 9);
  for (int i = 0; i < 1000; ++i) {
    const Config k = random_config(rng);
    const V w1 = random_unit(rng);
    double t0, t1, w, inv;
    if (!gradients::plane_ray_solve(k.a0, k.w0, w1, k.c, k.d, t0, t1, w, inv)) continue;
    const V p = k.a0 + t0 * k.w0 + t1 * w1, q = k.c + w * k.d;
    CHECK((p - q).norm() < 1e-9 * (1.0 + std::abs(t0) + std::abs(t1) + std::abs(w)));
    CHECK(std::abs(inv * gradients::plane_det(k.w0, w1, k.d) - 1.0) < 1e-9);
  }
}
