// Jacobians of the shift map vs the determinant of central finite differences of the map
// itself, in the same parameterization (solid angle of every sampled direction, charts
// (a, b) -> normalize(w + a s + b t) with (s, t) orthonormal tangents of w), all in
// double with analytic planes and spheres. Configurations: diffuse (reconnection onto
// planes and spheres), glossy (half-vector reflection), glass (half-vector refraction,
// entering and leaving), and a mixed chain glossy -> mirror -> diffuse -> reconnection
// whose 4x4 determinant must equal the product of the per-step factors (mirror: 1).
// The distribution of relative errors is printed; every case must be <= 1e-4.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/rng.h"
#include "gradients/jacobians.h"
#include "tests/support/direction_chart.h"

using namespace dp;
using namespace dp::gradients;

namespace {
using Chart = test::DirectionChart;
using test::fd_det;

struct Surface {  // plane (n, point) or sphere (center, radius)
  bool sphere = false;
  Vec3d a, n;
  double r = 0;
  double hit(const Vec3d& o, const Vec3d& d) const {
    if (!sphere) return (a - o).dot(n) / d.dot(n);
    const Vec3d oc = o - a;
    const double b = oc.dot(d), c = oc.squaredNorm() - r * r, disc = b * b - c;
    if (disc < 0) return -1;
    const double t0 = -b - std::sqrt(disc);
    return t0 > 1e-9 ? t0 : -b + std::sqrt(disc);
  }
  Vec3d normal(const Vec3d& p) const { return sphere ? Vec3d((p - a).normalized()) : n; }
};

Vec3d rand_dir(core::Rng& rng) {
  for (;;) {
    const Vec3d v(2 * rng.uniform_double() - 1, 2 * rng.uniform_double() - 1, 2 * rng.uniform_double() - 1);
    if (v.squaredNorm() > 0.01 && v.squaredNorm() < 1) return v.normalized();
  }
}
Vec3d rand_upper(core::Rng& rng, double min_z = 0.15) {
  for (;;) {
    Vec3d v = rand_dir(rng);
    if (std::abs(v.z()) >= min_z) return v.z() < 0 ? Vec3d(-v) : v;
  }
}


struct Report {
  std::vector<double> err;
  void add(double e) { err.push_back(e); }
  void print(const char* name) {
    std::sort(err.begin(), err.end());
    const auto q = [&](double f) { return err[std::min(err.size() - 1, size_t(f * double(err.size())))]; };
    std::printf("jacobian %-22s n=%zu  median %.2e  p90 %.2e  p99 %.2e  max %.2e\n", name, err.size(), q(0.5),
                q(0.9), q(0.99), err.back());
  }
  double max() const { return err.empty() ? 1.0 : *std::max_element(err.begin(), err.end()); }
};

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }
}  // namespace

TEST_CASE("Jacobian of reconnection vs finite differences (diffuse: planes and spheres)", "[unit]") {
  core::Rng rng(11, 0);
  Report rep, wrong;
  for (int i = 0; i < 400; ++i) {
    Surface s;
    s.sphere = i % 2 == 1;
    s.a = Vec3d(rng.uniform_double() - 0.5, rng.uniform_double() - 0.5, 3.0 + rng.uniform_double());
    s.n = (Vec3d(0, 0, -1) + 0.4 * rand_dir(rng)).normalized();
    s.r = 0.5 + rng.uniform_double();
    const Vec3d xb(rng.uniform_double() - 0.5, rng.uniform_double() - 0.5, 0);
    const Vec3d xo = xb + 0.3 * rand_dir(rng);
    const Vec3d target_dir = (s.a + (s.sphere ? -s.r : 0.3) * Vec3d(0, 0, 1) + 0.2 * rand_dir(rng) - xb);
    const double t0 = s.hit(xb, target_dir.normalized());
    if (!(t0 > 0)) continue;
    const Vec3d target = xb + t0 * target_dir.normalized();
    const Vec3d n = s.normal(target);
    if (std::abs(n.dot(target_dir.normalized())) < 0.1 || std::abs(n.dot((target - xo).normalized())) < 0.1) continue;
    auto map = [&](const std::vector<Vec3d>& x, std::vector<Vec3d>& y) {
      const double t = s.hit(xb, x[0]);
      if (!(t > 0)) return false;
      y = {(xb + t * x[0] - xo).normalized()};
      return true;
    };
    const double fd = fd_det({Chart(target_dir)}, {Chart(target - xo)}, map);
    const double J = reconnection_jacobian(xb, xo, target, n);
    rep.add(rel(J, fd));
    const double d2b = (target - xb).squaredNorm(), d2o = (target - xo).squaredNorm();
    wrong.add(rel(d2b / d2o, fd));  // distance ratio alone (cosines forgotten)
  }
  rep.print("reconnection");
  REQUIRE(rep.err.size() > 200);
  REQUIRE(rep.max() <= 1e-4);
  std::sort(wrong.err.begin(), wrong.err.end());
  REQUIRE(wrong.err[wrong.err.size() / 2] > 1e-2);  // a wrong formula is caught
}

TEST_CASE("Jacobian of half-vector reflection vs finite differences (glossy)", "[unit]") {
  core::Rng rng(12, 0);
  Report rep;
  for (int i = 0; i < 400; ++i) {
    const Vec3d wi = rand_upper(rng), wi_o = rand_upper(rng), wo = rand_upper(rng);
    const Vec3d h = reflection_half_vector(wi, wo);
    const Vec3d wo_o = reflect_about(wi_o, h);
    auto map = [&](const std::vector<Vec3d>& x, std::vector<Vec3d>& y) {
      y = {reflect_about(wi_o, reflection_half_vector(wi, x[0]))};
      return true;
    };
    const double fd = fd_det({Chart(wo)}, {Chart(wo_o)}, map);
    if (!(fd > 1e-3)) continue;
    rep.add(rel(reflection_jacobian(wo, wo_o, h), fd));
  }
  rep.print("half-vector reflection");
  REQUIRE(rep.err.size() > 300);
  REQUIRE(rep.max() <= 1e-4);
}

TEST_CASE("Jacobian of half-vector refraction vs finite differences (glass, both sides)", "[unit]") {
  core::Rng rng(13, 0);
  Report rep;
  const double etas[] = {1.5, 1.0 / 1.5, 1.33};
  for (int i = 0; i < 600; ++i) {
    const double eta = etas[i % 3];
    Vec3d wi = rand_upper(rng, 0.2), wi_o = rand_upper(rng, 0.2);
    if (i % 2) wi.z() = -wi.z(), wi_o.z() = -wi_o.z();  // leaving instead of entering
    const Vec3d m = (Vec3d(0, 0, 1) + 0.3 * rand_dir(rng)).normalized();
    const auto wo = refract_about(wi, m, eta);
    if (!wo || wo->z() * wi.z() >= 0) continue;
    const auto h = refraction_half_vector(wi, *wo, eta);
    REQUIRE(h);
    const auto wo_o = refract_about(wi_o, *h, eta);
    if (!wo_o || wo_o->z() * wi_o.z() >= 0) continue;
    // The refraction of wi about h reproduces wo (the copy is consistent).
    REQUIRE((*refract_about(wi, *h, eta) - *wo).norm() < 1e-9);
    auto map = [&](const std::vector<Vec3d>& x, std::vector<Vec3d>& y) {
      const auto hh = refraction_half_vector(wi, x[0], eta);
      if (!hh) return false;
      const auto r = refract_about(wi_o, *hh, eta);
      if (!r) return false;
      y = {*r};
      return true;
    };
    const double fd = fd_det({Chart(*wo)}, {Chart(*wo_o)}, map);
    if (!(fd > 1e-3) || !(fd < 1e3)) continue;
    rep.add(rel(refraction_jacobian(wi, *wo, wi_o, *wo_o, eta), fd));
  }
  rep.print("half-vector refraction");
  REQUIRE(rep.err.size() > 200);
  REQUIRE(rep.max() <= 1e-4);
}

TEST_CASE("Jacobian of a mixed chain glossy -> mirror -> diffuse -> reconnection vs 4x4 finite differences", "[unit]") {
  core::Rng rng(14, 0);
  Report rep;
  // Frames: x_1 and x'_1 lie on the plane z = 0 (local frame = world frame).
  const Surface mirror{false, Vec3d(0, 0, 2), Vec3d(0, 0, -1), 0};
  const Surface diffuse{false, Vec3d(0, 0, 0.0), Vec3d(0, 0, 1), 0};
  for (int i = 0; i < 300; ++i) {
    const Surface end{true, Vec3d(rng.uniform_double() - 0.5, rng.uniform_double() - 0.5, 1.2), Vec3d(0, 0, 1),
                      0.3 + 0.2 * rng.uniform_double()};
    const Vec3d x1(rng.uniform_double() - 0.5, rng.uniform_double() - 0.5, 0), x1o = x1 + Vec3d(0.05, -0.03, 0);
    const Vec3d wi = rand_upper(rng, 0.3), wi_o = (wi + 0.1 * rand_dir(rng)).normalized();
    if (wi_o.z() < 0.2) continue;
    const Vec3d w1 = rand_upper(rng, 0.4);
    const Vec3d x3dir_probe(0, 0, 1);
    (void)x3dir_probe;
    // Base chain, as a function of (w1, w3).
    struct Chain {
      Vec3d x3, x3o, x4, w1o, w3o;
      double J = 0;
      bool ok = false;
    };
    auto run = [&](const Vec3d& a1, const Vec3d& a3) {
      Chain c;
      const double t2 = mirror.hit(x1, a1);
      if (!(t2 > 0)) return c;
      const Vec3d x2 = x1 + t2 * a1, r2 = reflect_about(-a1, mirror.n);  // delta: mirror
      const double t3 = diffuse.hit(x2, r2);
      if (!(t3 > 0)) return c;
      c.x3 = x2 + t3 * r2;
      const double t4 = end.hit(c.x3, a3);
      if (!(t4 > 0)) return c;
      c.x4 = c.x3 + t4 * a3;
      // Offset: half-vector copy at x'_1, mirror at x'_2, then reconnect x'_3 -> x_4.
      const Vec3d h = reflection_half_vector(wi, a1);
      c.w1o = reflect_about(wi_o, h);
      const double t2o = mirror.hit(x1o, c.w1o);
      if (!(t2o > 0)) return c;
      const Vec3d x2o = x1o + t2o * c.w1o, r2o = reflect_about(-c.w1o, mirror.n);
      const double t3o = diffuse.hit(x2o, r2o);
      if (!(t3o > 0)) return c;
      c.x3o = x2o + t3o * r2o;
      c.w3o = (c.x4 - c.x3o).normalized();
      c.J = reflection_jacobian(a1, c.w1o, h) * 1.0 * reconnection_jacobian(c.x3, c.x3o, c.x4, end.normal(c.x4));
      c.ok = true;
      return c;
    };
    const Vec3d w3 = (end.a - Vec3d(0, 0, end.r) + 0.15 * rand_dir(rng) - run(w1, Vec3d(0, 0, 1)).x3).normalized();
    const Chain c0 = run(w1, w3);
    if (!c0.ok || (c0.x3 - c0.x3o).norm() < 1e-3) continue;
    auto map = [&](const std::vector<Vec3d>& x, std::vector<Vec3d>& y) {
      const Chain c = run(x[0], x[1]);
      if (!c.ok) return false;
      y = {c.w1o, c.w3o};
      return true;
    };
    const double fd = fd_det({Chart(w1), Chart(w3)}, {Chart(c0.w1o), Chart(c0.w3o)}, map);
    if (!(fd > 1e-4) || !std::isfinite(fd)) continue;
    rep.add(rel(c0.J, fd));
  }
  rep.print("mixed chain (4x4)");
  REQUIRE(rep.err.size() > 100);
  REQUIRE(rep.max() <= 1e-4);
}
