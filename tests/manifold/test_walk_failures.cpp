// Failure statuses: total internal reflection, grazing, singular blocks (a focus),
// index-matched refraction. A failing walk must report why and never produce NaN/Inf.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/manifold/manifold_fixtures.h"

using namespace dp;
using namespace dp::test_mf;

namespace {

ChainVertex at(const scene::Scene& s, int shape, const Vec3d& p, Interaction type = Interaction::reflection,
               double eta = 1) {
  ChainVertex v;
  v.shape = shape;
  v.prim = 0;
  REQUIRE(local_frame(*s.shapes()[size_t(shape)], 0, p, v.f));
  v.type = type;
  v.eta = eta;
  return v;
}

void check_failure(const WalkResult& r, WalkStatus expect) {
  INFO("got " << to_string(r.status) << ", expected " << to_string(expect));
  CHECK(r.status == expect);
  CHECK(std::isfinite(r.distance));
  for (const auto& v : r.chain.v) CHECK(v.p().allFinite());
}

}  // namespace

TEST_CASE("total internal reflection in a glass wedge is reported", "[unit]") {
  Builder b;
  const Material glass{Interaction::refraction, 1.5};
  const int top = b.quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, glass);
  // 45 degree exit face z = x - 0.5: a vertical ray meets it at 45 deg > critical 41.8 deg.
  const int face = b.quad({-2, -2, -2.5f}, {-2, 2, -2.5f}, {2, 2, 1.5f}, {2, -2, 1.5f}, glass);
  const int recv = b.quad({-5, -5, -3}, {5, -5, -3}, {5, 5, -3}, {-5, 5, -3}, std::nullopt);
  auto s = b.commit();
  Chain c;
  c.v = {make_point(Vec3d(0, 0, 1)), at(*s, top, Vec3d(0, 0, 0), Interaction::refraction, 1.5),
         at(*s, face, Vec3d(0, 0, -0.5), Interaction::refraction, 1.5), at(*s, recv, Vec3d(0, 0, -3))};
  check_failure(walk(*s, c, Vec3d(0.1, 0, -3), WalkSettings{}), WalkStatus::total_internal_reflection);
  CHECK(std::isfinite(constraint_residual(c)));  // the manual chain violates its constraints: finite, not NaN
}

TEST_CASE("grazing configurations are reported, not NaN", "[unit]") {
  Builder b;
  const int mirror = b.quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Material{});
  const int recv = b.quad({-3, -3, 1}, {-3, 3, 1}, {3, 3, 1}, {3, -3, 1}, std::nullopt);
  auto s = b.commit();
  Chain c;
  c.v = {make_point(Vec3d(-1, 0, 0)), at(*s, mirror, Vec3d(0, 0, 0)), at(*s, recv, Vec3d(1, 0, 1))};
  std::vector<Mat2d> T;
  CHECK(tangent_map(c, T) == WalkStatus::grazing);
  double G = -1;
  CHECK(generalized_geometry(c, G) == WalkStatus::grazing);
  const WalkResult r = walk(*s, c, Vec3d(1.2, 0, 1), WalkSettings{});
  CHECK_FALSE(r.ok());
  CHECK(std::isfinite(r.distance));
}

TEST_CASE("a focus (concave mirror image plane) is a singular block", "[unit]") {
  Builder b;
  const int mirror = b.sphere({0, 0, 0}, 2.0f, Material{}, /*flip=*/true);
  const int recv = b.quad({-1, -0.5f, -0.5f}, {-1, 0.5f, -0.5f}, {-1, 0.5f, 0.5f}, {-1, -0.5f, 0.5f}, std::nullopt);
  auto s = b.commit();
  // Mirror equation 1/1.5 + 1/3 = 2/R with R = 2: x0 at 0.5 images onto x = -1.
  Chain c;
  c.v = {make_point(Vec3d(0.5, 0, 0)), at(*s, mirror, Vec3d(2, 0, 0)), at(*s, recv, Vec3d(-1, 0, 0))};
  std::vector<Mat2d> T;
  CHECK(tangent_map(c, T) == WalkStatus::singular);
  double det = 1;
  CHECK(constraint_determinant(c, det) == WalkStatus::singular);
  check_failure(walk(*s, c, Vec3d(-1, 0.1, 0.05), WalkSettings{}), WalkStatus::singular);
  // Moving the start off the conjugate point makes the block regular again.
  c.v[0] = make_point(Vec3d(0.2, 0, 0));
  CHECK(tangent_map(c, T) == WalkStatus::ok);
}

TEST_CASE("index-matched refraction has no half vector", "[unit]") {
  Builder b;
  const int sheet = b.quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Material{Interaction::refraction, 1.0});
  const int recv = b.quad({-3, -3, -1}, {3, -3, -1}, {3, 3, -1}, {-3, 3, -1}, std::nullopt);
  auto s = b.commit();
  Chain c;
  c.v = {make_point(Vec3d(0, 0, 1)), at(*s, sheet, Vec3d(0, 0, 0), Interaction::refraction, 1.0),
         at(*s, recv, Vec3d(0, 0, -1))};
  std::vector<Mat2d> T;
  CHECK(tangent_map(c, T) == WalkStatus::index_matched);
  check_failure(walk(*s, c, Vec3d(0.2, 0, -1), WalkSettings{}), WalkStatus::index_matched);
}
