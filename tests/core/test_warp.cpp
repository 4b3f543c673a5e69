#include <catch2/catch.hpp>

#include "core/rng.h"
#include "core/warp.h"

using namespace dp;
using namespace dp::core;

namespace {
// Round trip u -> warp(u) -> inverse -> u on random points of the open unit square.
template <typename F, typename G>
void check_round_trip(F forward, G inverse, float tol = 2e-4f) {
  Rng rng(7, 1);
  for (int i = 0; i < 20000; ++i) {
    Vec2 u = rng.uniform2();
    u = u.cwiseMax(Vec2(1e-4f, 1e-4f)).cwiseMin(Vec2(1 - 1e-4f, 1 - 1e-4f));
    const Vec2 back = inverse(forward(u));
    INFO("u = " << u.transpose() << " back = " << back.transpose());
    REQUIRE((back - u).cwiseAbs().maxCoeff() < tol);
  }
}
}  // namespace

TEST_CASE("warp inverses round-trip", "[unit]") {
  check_round_trip(warp::square_to_uniform_disk_concentric, warp::uniform_disk_concentric_to_square);
  check_round_trip(warp::square_to_cosine_hemisphere, warp::cosine_hemisphere_to_square);
  check_round_trip(warp::square_to_uniform_sphere, warp::uniform_sphere_to_square);
  check_round_trip(warp::square_to_uniform_hemisphere, warp::uniform_hemisphere_to_square);
  check_round_trip(warp::square_to_uniform_triangle, warp::uniform_triangle_to_square);
  check_round_trip([](const Vec2& u) { return warp::square_to_uniform_cone(u, 0.7f); },
                   [](const Vec3& w) { return warp::uniform_cone_to_square(w, 0.7f); });
}

TEST_CASE("warps land in their domain", "[unit]") {
  Rng rng(3, 0);
  for (int i = 0; i < 10000; ++i) {
    const Vec2 u = rng.uniform2();
    REQUIRE(warp::square_to_uniform_disk_concentric(u).norm() <= 1.0f + 1e-6f);
    REQUIRE(std::abs(warp::square_to_uniform_sphere(u).norm() - 1.0f) < 1e-5f);
    REQUIRE(warp::square_to_cosine_hemisphere(u).z() >= 0.0f);
    const Vec2 b = warp::square_to_uniform_triangle(u);
    REQUIRE(b.x() >= 0.0f);
    REQUIRE(b.y() >= 0.0f);
    REQUIRE(b.x() + b.y() <= 1.0f + 1e-6f);
    REQUIRE(warp::square_to_uniform_cone(u, 0.9f).z() >= 0.9f - 1e-6f);
  }
}

TEST_CASE("frames are orthonormal for any normal", "[unit]") {
  Rng rng(11, 0);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = warp::square_to_uniform_sphere(rng.uniform2());
    const Frame f = Frame::from_normal(n);
    REQUIRE(std::abs(f.s.dot(f.t)) < 1e-5f);
    REQUIRE(std::abs(f.s.dot(f.n)) < 1e-5f);
    REQUIRE(std::abs(f.s.norm() - 1) < 1e-5f);
    REQUIRE(std::abs(f.t.norm() - 1) < 1e-5f);
    REQUIRE((f.s.cross(f.t) - f.n).norm() < 1e-4f);  // right-handed
    const Vec3 v = warp::square_to_uniform_sphere(rng.uniform2());
    REQUIRE((f.to_world(f.to_local(v)) - v).norm() < 1e-5f);
  }
}
