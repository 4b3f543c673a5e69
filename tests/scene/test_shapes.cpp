// Shapes: mesh clean-up, area sampling, surface differential geometry (against finite
// differences) and sphere intersection edge cases.
#include <boost/math/special_functions/gamma.hpp>
#include <catch2/catch.hpp>

#include "tests/scene/geometry_test_util.h"

using namespace dp;
using namespace dp::scene;

namespace {

SurfacePoint mesh_point(const TriangleMesh& m, int prim, const Vec2& b) {
  SurfacePoint sp;
  Ray r;
  r.o = Vec3(0, 0, 0);
  r.d = Vec3(0, 0, 1);
  m.fill_surface(prim, b, r, 1.0f, sp);
  return sp;
}

// Surface point of a sphere at spherical coordinates (u, v) (Mitsuba parameterization),
// reached by a ray from outside.
SurfacePoint sphere_point(const Sphere& s, double u, double v) {
  const double phi = 2 * kPiD * u, theta = kPiD * v;
  const Vec3d dir(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  Ray r;
  r.o = s.center() + (3.0 * double(s.radius()) * dir).cast<float>();
  r.d = (-dir).cast<float>();
  float t = 0;
  REQUIRE(s.intersect(r, t));
  SurfacePoint sp;
  s.fill_surface(0, Vec2(0, 0), r, t, sp);
  return sp;
}

}  // namespace

TEST_CASE("mesh finalize drops and counts degenerate triangles", "[unit]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto m = std::make_unique<TriangleMesh>();
  m->positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0), Vec3(nan, 0, 0), Vec3(0, 0, 2)};
  m->triangles = {{0, 1, 2},   // area 0.5
                  {0, 1, 1},   // repeated vertex
                  {0, 1, 3},   // collinear
                  {0, 4, 2},   // non-finite vertex
                  {0, 1, 5}};  // area 1
  m->finalize();
  CHECK(m->degenerate_skipped == 3);
  REQUIRE(m->triangles.size() == 2);
  CHECK(m->area() == Approx(1.5f));
  CHECK(m->triangle_area(1) == Approx(1.0f));
  const Bounds3 b = m->bounds();  // only vertices of kept triangles
  CHECK((b.lo - Vec3(0, 0, 0)).norm() < 1e-6f);
  CHECK((b.hi - Vec3(1, 1, 2)).norm() < 1e-6f);
  // Index out of range is a user error (bad mesh file), not a silent skip.
  auto bad = std::make_unique<TriangleMesh>();
  bad->positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  bad->triangles = {{0, 1, 3}};
  CHECK_THROWS(bad->finalize());
}

TEST_CASE("mesh sample_area is uniform by area", "[stat]") {
  // A triangle of area 1 next to a 3 x 2 rectangle made of two triangles. Check the
  // fraction of samples on the small triangle (binomial) and the uniformity over a grid
  // of the rectangle (Pearson chi-square).
  auto m = test::make_mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(4, 0, 0), Vec3(4, 2, 0)},
                           {{0, 1, 2}, {1, 3, 4}, {1, 4, 2}});
  REQUIRE(m->area() == Approx(7.0f));  // 1 + 3 + 3
  const int n = 200000, gx = 8, gy = 4;
  std::vector<double> grid(size_t(gx * gy), 0.0);
  core::Rng rng(3, 0);
  int left = 0;
  for (int i = 0; i < n; ++i) {
    const PositionSample s = m->sample_area(rng.uniform2());
    REQUIRE(s.pdf_area == Approx(1.0f / 7.0f));
    REQUIRE((s.n - Vec3(0, 0, 1)).norm() < 1e-6f);
    REQUIRE(std::abs(s.p.z()) < 1e-6f);
    if (s.p.x() < 1.0f) ++left;
    if (s.p.x() >= 1.0f) {  // the rectangle [1,4] x [0,2] is covered exactly
      const int ix = std::min(gx - 1, int((s.p.x() - 1.0f) / 3.0f * gx));
      const int iy = std::min(gy - 1, int(s.p.y() / 2.0f * gy));
      grid[size_t(iy * gx + ix)] += 1;
    }
  }
  const double p_left = 1.0 / 7.0;
  CHECK(std::abs(left - n * p_left) < 4.0 * std::sqrt(n * p_left * (1 - p_left)));
  const double expected = double(n - left) / (gx * gy);
  double stat = 0;
  for (double c : grid) stat += sqr(c - expected) / expected;
  const double p_value = boost::math::gamma_q((gx * gy - 1) / 2.0, stat / 2.0);
  INFO("chi2 " << stat << " p " << p_value);
  CHECK(p_value > 0.001);
}

TEST_CASE("mesh fill_surface: position, normal, default uvs, tangents", "[unit]") {
  auto m = test::make_mesh({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 1)}, {{0, 1, 2}});
  const Vec2 b(0.25f, 0.5f);
  const SurfacePoint sp = mesh_point(*m, 0, b);
  CHECK((sp.p - Vec3(0.5f, 1.5f, 0.5f)).norm() < 1e-6f);
  const Vec3 ng = Vec3(2, 0, 0).cross(Vec3(0, 3, 1)).normalized();
  CHECK((sp.ng - ng).norm() < 1e-6f);
  CHECK((sp.uv - b).norm() < 1e-6f);  // no uvs: uv = (b1, b2)
  CHECK((sp.dpdu - Vec3(2, 0, 0)).norm() < 1e-5f);
  CHECK((sp.dpdv - Vec3(0, 3, 1)).norm() < 1e-5f);
  CHECK((sp.shading.n - ng).norm() < 1e-6f);
  CHECK(sp.shading.s.dot(Vec3(1, 0, 0)) > 0.999f);
  CHECK(sp.dndu.norm() == 0.0f);
  CHECK(sp.dndv.norm() == 0.0f);
  // Explicit uvs: e_k = dpdu du_k + dpdv dv_k.
  m->uvs = {Vec2(0.1f, 0.2f), Vec2(0.7f, 0.1f), Vec2(0.3f, 0.9f)};
  m->finalize();  // per-triangle frames are built by finalize()
  const SurfacePoint su = mesh_point(*m, 0, b);
  CHECK((su.uv - Vec2(0.35f, 0.525f)).norm() < 1e-6f);
  CHECK((su.dpdu * 0.6f + su.dpdv * -0.1f - Vec3(2, 0, 0)).norm() < 1e-4f);
  CHECK((su.dpdu * 0.2f + su.dpdv * 0.7f - Vec3(0, 3, 1)).norm() < 1e-4f);
  // Degenerate uvs: an orthonormal tangent frame, still usable.
  m->uvs = {Vec2(0.5f, 0.5f), Vec2(0.5f, 0.5f), Vec2(0.5f, 0.5f)};
  m->finalize();
  const SurfacePoint sd = mesh_point(*m, 0, b);
  CHECK(std::abs(sd.dpdu.norm() - 1.0f) < 1e-5f);
  CHECK(std::abs(sd.dpdu.dot(sd.ng)) < 1e-5f);
  CHECK(std::abs(sd.dpdu.dot(sd.dpdv)) < 1e-5f);
}

TEST_CASE("mesh fill_surface: interpolated normals and their derivatives", "[unit]") {
  auto m = test::make_mesh({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 1)}, {{0, 1, 2}});
  m->normals = {Vec3(0.1f, -0.3f, 1).normalized(), Vec3(0.5f, 0.2f, 1).normalized(), Vec3(-0.3f, 0.1f, 1).normalized()};
  for (const bool with_uvs : {false, true}) {
    if (with_uvs) {
      m->uvs = {Vec2(0.1f, 0.2f), Vec2(0.7f, 0.1f), Vec2(0.3f, 0.9f)};
      m->finalize();
    }
    const Vec2 b(0.3f, 0.2f);
    const SurfacePoint sp = mesh_point(*m, 0, b);
    const Vec3 expected = (0.5f * m->normals[0] + 0.3f * m->normals[1] + 0.2f * m->normals[2]).normalized();
    CHECK((sp.shading.n - expected).norm() < 1e-5f);
    CHECK(std::abs(sp.shading.s.dot(sp.shading.n)) < 1e-5f);
    // Finite differences in (u, v): barycentric steps with d(uv) = (h, 0) and (0, h).
    const Vec2 uv0 = with_uvs ? m->uvs[0] : Vec2(0, 0), uv1 = with_uvs ? m->uvs[1] : Vec2(1, 0),
               uv2 = with_uvs ? m->uvs[2] : Vec2(0, 1);
    Eigen::Matrix2f jac;
    jac << uv1.x() - uv0.x(), uv2.x() - uv0.x(), uv1.y() - uv0.y(), uv2.y() - uv0.y();
    const float h = 1e-3f;
    for (int k = 0; k < 2; ++k) {
      const Vec2 db = jac.inverse() * (k == 0 ? Vec2(h, 0) : Vec2(0, h));
      const SurfacePoint a = mesh_point(*m, 0, b + db), c = mesh_point(*m, 0, b - db);
      const Vec3 dn_fd = (a.shading.n - c.shading.n) / (2 * h);
      const Vec3 dp_fd = (a.p - c.p) / (2 * h);
      const Vec3 dn = k == 0 ? sp.dndu : sp.dndv, dp = k == 0 ? sp.dpdu : sp.dpdv;
      INFO("with_uvs " << with_uvs << " k " << k);
      CHECK((dn - dn_fd).norm() < 2e-3f * std::max(1.0f, dn.norm()));
      CHECK((dp - dp_fd).norm() < 2e-3f * dp.norm());
      CHECK(dn.norm() > 1e-3f);
    }
  }
  // smooth = false ignores the normals.
  m->smooth = false;
  const SurfacePoint flat = mesh_point(*m, 0, Vec2(0.3f, 0.2f));
  CHECK((flat.shading.n - flat.ng).norm() < 1e-6f);
  CHECK(flat.dndu.norm() == 0.0f);
  // Normals opposite to the winding are kept, not flipped into ng's hemisphere.
  m->smooth = true;
  for (auto& n : m->normals) n = -n;
  const SurfacePoint back = mesh_point(*m, 0, Vec2(0.3f, 0.2f));
  CHECK(back.shading.n.dot(back.ng) < 0.0f);
}

TEST_CASE("sphere intersection: outside, inside, tangent, behind, ranges", "[unit]") {
  Sphere s(Vec3(0, 0, 0), 1.0f);
  Ray r;
  float t = -1;
  r.o = Vec3(0, 0, -5);
  r.d = Vec3(0, 0, 1);
  REQUIRE(s.intersect(r, t));
  CHECK(t == Approx(4.0f));
  r.tmax = 3.5f;
  CHECK_FALSE(s.intersect(r, t));
  r.tmax = kInfinity;
  r.tmin = 4.5f;  // past the entry point: the exit point
  REQUIRE(s.intersect(r, t));
  CHECK(t == Approx(6.0f));
  // Inside: the far hit.
  r = Ray{Vec3(0, 0, 0.5f), Vec3(0, 0, 1)};
  REQUIRE(s.intersect(r, t));
  CHECK(t == Approx(0.5f));
  r.d = Vec3(0, 0, -1);
  REQUIRE(s.intersect(r, t));
  CHECK(t == Approx(1.5f));
  // Behind the origin.
  r = Ray{Vec3(0, 0, 3), Vec3(0, 0, 1)};
  CHECK_FALSE(s.intersect(r, t));
  // Tangent and near-tangent rays.
  r = Ray{Vec3(1.0001f, 0, -5), Vec3(0, 0, 1)};
  CHECK_FALSE(s.intersect(r, t));
  r = Ray{Vec3(0.9999f, 0, -5), Vec3(0, 0, 1)};
  REQUIRE(s.intersect(r, t));
  CHECK(double(t) == Approx(5.0 - std::sqrt(1.0 - sqr(double(0.9999f)))).epsilon(1e-4));
  r = Ray{Vec3(1, 0, -5), Vec3(0, 0, 1)};
  if (s.intersect(r, t)) CHECK(t == Approx(5.0f).epsilon(1e-3));
  // Far away: the hit is accurate to float precision (no cancellation).
  Sphere small(Vec3(0, 0, 1e4f), 0.01f);
  r = Ray{Vec3(0.005f, 0, 0), Vec3(0, 0, 1)};
  REQUIRE(small.intersect(r, t));
  CHECK(double(t) == Approx(1e4 - std::sqrt(1e-4 - 0.25e-4)).epsilon(1e-6));
  // Bounds.
  const Bounds3 b = s.bounds();
  CHECK((b.lo - Vec3(-1, -1, -1)).norm() < 1e-6f);
  CHECK((b.hi - Vec3(1, 1, 1)).norm() < 1e-6f);
}

TEST_CASE("sphere fill_surface: normals, uv and derivatives against finite differences", "[unit]") {
  Sphere s(Vec3(0.5f, -1, 2), 1.5f);
  for (const bool flip : {false, true}) {
    s.flip_normals = flip;
    const double u = 0.3, v = 0.35, h = 1e-4;
    const SurfacePoint sp = sphere_point(s, u, v);
    const Vec3 out = (sp.p - s.center()) / s.radius();
    CHECK(std::abs((sp.p - s.center()).norm() - s.radius()) < 1e-5f);
    CHECK((sp.ng - (flip ? Vec3(-out) : out)).norm() < 1e-5f);
    CHECK((sp.shading.n - sp.ng).norm() < 1e-6f);
    CHECK(double(sp.uv.x()) == Approx(u).epsilon(1e-5));
    CHECK(double(sp.uv.y()) == Approx(v).epsilon(1e-5));
    const SurfacePoint pu = sphere_point(s, u + h, v), mu = sphere_point(s, u - h, v);
    const SurfacePoint pv = sphere_point(s, u, v + h), mv = sphere_point(s, u, v - h);
    const auto fd = [&](const Vec3& a, const Vec3& b) { return Vec3((a - b) / float(2 * h)); };
    CHECK((sp.dpdu - fd(pu.p, mu.p)).norm() < 1e-2f * sp.dpdu.norm());
    CHECK((sp.dpdv - fd(pv.p, mv.p)).norm() < 1e-2f * sp.dpdv.norm());
    CHECK((sp.dndu - fd(pu.ng, mu.ng)).norm() < 1e-2f * sp.dndu.norm());
    CHECK((sp.dndv - fd(pv.ng, mv.ng)).norm() < 1e-2f * sp.dndv.norm());
  }
  // Sampled points: on the surface, pdf 1 / area, normal consistent with fill_surface.
  s.flip_normals = false;
  core::Rng rng(4, 0);
  for (int i = 0; i < 100; ++i) {
    const PositionSample ps = s.sample_area(rng.uniform2());
    REQUIRE(std::abs((ps.p - s.center()).norm() - s.radius()) < 1e-5f);
    REQUIRE((ps.n - (ps.p - s.center()).normalized()).norm() < 1e-5f);
    REQUIRE(ps.pdf_area == Approx(1.0f / (4.0f * kPi * 1.5f * 1.5f)));
  }
}
