// Tangent map, constraint determinant and generalized geometry term against central
// finite differences of the walk itself. Walks run to 1e-13 so the walk's own error
// (1e-13 / eps) stays far below the truncation error O(eps^2) ~ 1e-8 of eps = 1e-4;
// the required agreement (relative 1e-4) is the issue's.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/manifold/manifold_fixtures.h"

using namespace dp;
using namespace dp::test_mf;

namespace {

constexpr double kEps = 1e-4;
constexpr double kRel = 1e-4;

WalkSettings tight() {
  WalkSettings ws;
  ws.tolerance = 1e-13;
  ws.max_iterations = 40;
  return ws;
}

struct Config {
  const char* name;
  std::unique_ptr<scene::Scene> scene;
  std::map<int, Material> spec;
  Chain chain;
};

// Scenes whose end lies on a plane (walk targets x_n + eps T stay on the surface).
std::vector<Config> configs(bool glossy) {
  std::vector<Config> out;
  auto target_of = [glossy](int k) { return glossy ? Vec2d(0.11 - 0.07 * k, -0.05 + 0.04 * k) : Vec2d(0, 0); };
  auto finish = [&](const char* name, Builder& b, const ChainVertex& x0, const Vec3d& dir, int n) {
    Config c;
    c.name = name;
    c.spec = b.specular;
    c.scene = b.commit();
    // The given direction, or the first of a deterministic fan around it that yields a
    // chain with n specular vertices.
    auto ch = trace_chain(*c.scene, c.spec, x0, dir, n, target_of);
    const Frame fr = Frame::from_normal(dir.normalized().cast<float>());
    for (int k = 1; !ch && k < 4000; ++k) {
      const double rad = 0.002 * k, ang = 0.7 * k;
      const Vec3d d = dir.normalized() + rad * (std::cos(ang) * fr.s.cast<double>() + std::sin(ang) * fr.t.cast<double>());
      ch = trace_chain(*c.scene, c.spec, x0, d, n, target_of);
    }
    INFO("tracing " << name);
    REQUIRE(ch);
    c.chain = *ch;
    out.push_back(std::move(c));
  };
  {
    Builder b;
    b.sphere({0, 0, 0}, 0.5f, Material{});
    b.quad({-3, -3, 1}, {-3, 3, 1}, {3, 3, 1}, {3, -3, 1}, std::nullopt);
    finish("sphere mirror", b, make_point(Vec3d(-1.0, 0.2, 0.9)), Vec3d(1.0, -0.15, -0.5), 1);
  }
  {
    Builder b;
    b.sphere({0, 0, 0}, 1.0f, Material{Interaction::refraction, 1.5});
    b.quad({-6, -6, -3}, {6, -6, -3}, {6, 6, -3}, {-6, 6, -3}, std::nullopt);
    finish("glass ball", b, make_point(Vec3d(0.4, 0.3, 3.0)), Vec3d(-0.2, -0.05, -1), 2);
  }
  {
    Builder b;
    b.sphere({0, 0, 1}, 0.6f, Material{Interaction::refraction, 1.33});
    // tilted mirror z = -0.5 + 0.3 x (normal up), receiver x = -4 facing +x
    b.quad({-3, -3, -1.4f}, {3, -3, 0.4f}, {3, 3, 0.4f}, {-3, 3, -1.4f}, Material{});
    b.quad({-4, -6, -6}, {-4, 6, -6}, {-4, 6, 6}, {-4, -6, 6}, std::nullopt);
    // into the water ball -> out -> tilted mirror -> wall
    finish("water ball + tilted mirror", b, make_point(Vec3d(0.5, 0.2, 3.0)), Vec3d(-0.3, -0.1, -1), 3);
  }
  return out;
}

// Chain with a smooth-normal mesh mirror (interpolated normals: dn != 0, flat geometry).
Config bumpy_mirror(bool glossy) {
  Builder b;
  auto m = std::make_unique<scene::TriangleMesh>();
  m->positions = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  m->normals = {Vec3(-0.3f, -0.2f, 1).normalized(), Vec3(0.25f, -0.1f, 1).normalized(),
                Vec3(0.2f, 0.3f, 1).normalized(), Vec3(-0.1f, 0.2f, 1).normalized()};
  m->triangles = {{0, 1, 2}, {0, 2, 3}};
  m->finalize();
  b.add(std::move(m), Material{});
  b.quad({-4, -4, 2}, {-4, 4, 2}, {4, 4, 2}, {4, -4, 2}, std::nullopt);
  Config c;
  c.name = "smooth-normal mirror";
  c.spec = b.specular;
  c.scene = b.commit();
  auto ch = trace_chain(*c.scene, c.spec, make_point(Vec3d(-0.5, 0.3, 1.2)), Vec3d(0.3, 0.1, -1), 1,
                        [glossy](int) { return glossy ? Vec2d(0.08, -0.03) : Vec2d(0, 0); });
  REQUIRE(ch);
  c.chain = *ch;
  return c;
}

Vec2d tcoords(const ChainVertex& v, const Vec3d& d) { return Vec2d(d.dot(v.f.T1), d.dot(v.f.T2)); }

void check_tangent_map(const Config& c) {
  INFO(c.name);
  const Chain& ch = c.chain;
  const int n = ch.n();
  std::vector<Mat2d> T;
  REQUIRE(tangent_map(ch, T) == WalkStatus::ok);
  std::vector<Mat2d> fd(size_t(n), Mat2d::Zero());
  const ChainVertex& end = ch.v[size_t(n)];
  for (int k = 0; k < 2; ++k) {
    const Vec3d dir = k == 0 ? end.f.T1 : end.f.T2;
    const WalkResult p = walk(*c.scene, ch, end.p() + kEps * dir, tight());
    const WalkResult m = walk(*c.scene, ch, end.p() - kEps * dir, tight());
    REQUIRE(p.ok());
    REQUIRE(m.ok());
    for (int i = 1; i < n; ++i)
      fd[size_t(i)].col(k) = tcoords(ch.v[size_t(i)], p.chain.v[size_t(i)].p() - m.chain.v[size_t(i)].p()) / (2 * kEps);
  }
  for (int i = 1; i < n; ++i) {
    const double err = (fd[size_t(i)] - T[size_t(i)]).norm() / T[size_t(i)].norm();
    INFO("vertex " << i << " analytic\n" << T[size_t(i)] << "\nfd\n" << fd[size_t(i)] << "\nrel err " << err);
    CHECK(err <= kRel);
  }
}

// Moves interior vertex i of a chain along its tangent (re-projected onto its surface).
Chain moved(const scene::Scene& s, const Chain& ch, int i, const Vec3d& d) {
  Chain c = ch;
  ChainVertex& v = c.v[size_t(i)];
  REQUIRE(local_frame(*s.shapes()[size_t(v.shape)], v.prim, v.p() + d, v.f));
  return c;
}

}  // namespace

TEST_CASE("tangent map matches central differences of the walk", "[unit]") {
  for (bool glossy : {false, true}) {
    for (auto& c : configs(glossy)) check_tangent_map(c);
    check_tangent_map(bumpy_mirror(glossy));
  }
}

TEST_CASE("half-vector-preserving map: |det B(x)| / |det B(x~)| matches the finite-difference Jacobian", "[unit]") {
  auto cs = configs(true);
  cs.push_back(bumpy_mirror(true));
  for (auto& c : cs) {
    INFO(c.name);
    const Chain& ch = c.chain;
    const int n = ch.n(), m = 2 * (n - 1);
    const ChainVertex& end = ch.v[size_t(n)];
    const Vec3d new_end = end.p() + 0.05 * end.f.T1 - 0.03 * end.f.T2;
    const WalkResult base = walk(*c.scene, ch, new_end, tight());
    REQUIRE(base.ok());
    double det_x, det_y;
    REQUIRE(constraint_determinant(ch, det_x) == WalkStatus::ok);
    REQUIRE(constraint_determinant(base.chain, det_y) == WalkStatus::ok);
    const double analytic = std::abs(det_x) / std::abs(det_y);
    Eigen::MatrixXd J(m, m);
    for (int i = 1; i < n; ++i) {
      for (int k = 0; k < 2; ++k) {
        const Vec3d dir = k == 0 ? ch.v[size_t(i)].f.T1 : ch.v[size_t(i)].f.T2;
        Vec3d plus_minus[2][8];
        for (int sgn = 0; sgn < 2; ++sgn) {
          Chain perturbed = moved(*c.scene, ch, i, (sgn == 0 ? kEps : -kEps) * dir);
          REQUIRE(set_targets_from_current(perturbed) == WalkStatus::ok);
          const WalkResult r = walk(*c.scene, perturbed, new_end, tight());
          REQUIRE(r.ok());
          for (int j = 1; j < n; ++j) plus_minus[sgn][j] = r.chain.v[size_t(j)].p();
        }
        for (int j = 1; j < n; ++j) {
          const Vec2d d = tcoords(base.chain.v[size_t(j)], plus_minus[0][j] - plus_minus[1][j]) / (2 * kEps);
          J(2 * (j - 1), 2 * (i - 1) + k) = d.x();
          J(2 * (j - 1) + 1, 2 * (i - 1) + k) = d.y();
        }
      }
    }
    const double numeric = std::abs(J.determinant());
    INFO("analytic " << analytic << " fd " << numeric);
    CHECK(std::abs(numeric - analytic) <= kRel * analytic);
  }
}

TEST_CASE("generalized geometry term equals projected solid angle per unit end area", "[unit]") {
  auto cs = configs(false);
  cs.push_back(bumpy_mirror(false));
  for (auto& c : cs) {
    INFO(c.name);
    const Chain& ch = c.chain;
    double G;
    REQUIRE(generalized_geometry(ch, G) == WalkStatus::ok);
    const ChainVertex& end = ch.v.back();
    const Vec3d x0 = ch.v[0].p();
    Vec3d w[4];
    const double h = 1e-4;
    const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k) {
      const WalkResult r = walk(*c.scene, ch, end.p() + h * (su[k] * end.f.T1 + sv[k] * end.f.T2), tight());
      REQUIRE(r.ok());
      w[k] = (r.chain.v[1].p() - x0).normalized();
    }
    // Solid angle of the spherical quad as two triangles (Van Oosterom & Strackee 1983).
    auto tri = [](const Vec3d& a, const Vec3d& b, const Vec3d& cc) {
      return 2.0 * std::atan2(std::abs(a.dot(b.cross(cc))), 1.0 + a.dot(b) + b.dot(cc) + cc.dot(a));
    };
    const double omega = tri(w[0], w[1], w[2]) + tri(w[0], w[2], w[3]);
    const double numeric = omega / (4 * h * h);  // x0 is a point: no cos theta_0
    INFO("G " << G << " numeric " << numeric);
    CHECK(std::abs(numeric - G) <= kRel * G);
  }
}
