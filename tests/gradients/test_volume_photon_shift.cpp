// G-VPM's kernel-space shifts (Gruson et al. 2018, Sec. 4.1-4.2; gradients/volume_photon_shift.h):
//  * the mixed shift (Eq. 16) maps every photon of the base kernel into the offset kernel,
//    the mixed shift back from d' to d returns it (bijection), all three branches occur,
//    and its Jacobian determinant is 1 in magnitude (central differences away from the
//    branch boundaries); the reflection without its factor 2 is rejected by the same
//    checks (it leaves photons non-invertible);
//  * the gather-point shift copies the distance and fails past the offset segment's end.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "gradients/volume_photon_shift.h"

using namespace dp;
using gradients::PhotonShiftFault;
using gradients::PhotonShiftKind;

namespace {

Vec3 in_ball(core::Rng& rng, const Vec3& c, float r) {
  for (;;) {
    const Vec3 v(2.0f * rng.uniform() - 1.0f, 2.0f * rng.uniform() - 1.0f, 2.0f * rng.uniform() - 1.0f);
    if (v.squaredNorm() <= 1.0f) return c + r * v;
  }
}

struct Tally {
  int64_t count[3] = {0, 0, 0};
  int64_t outside = 0, not_inverted = 0, n = 0;
};

// Random configurations: r in [0.1, 1], |d' - d| from 0.01 r to 2.5 r (no overlap beyond 2r).
Tally run(PhotonShiftFault fault, uint64_t seed) {
  core::Rng rng(seed, 0);
  Tally t;
  for (int k = 0; k < 20000; ++k) {
    const float r = 0.1f + 0.9f * rng.uniform();
    const Vec3 d = in_ball(rng, Vec3::Zero(), 3.0f);
    const Vec3 dir = in_ball(rng, Vec3::Zero(), 1.0f).normalized();
    const Vec3 d_off = d + dir * (r * (0.01f + 2.49f * rng.uniform()));
    const Vec3 b = in_ball(rng, d, r);
    const auto s = gradients::mixed_photon_shift(b, d, d_off, r, fault);
    ++t.count[int(s.kind)];
    ++t.n;
    const float tol = 1e-5f * (1.0f + d.norm() + r);
    if ((s.b - d_off).norm() > r + tol) ++t.outside;
    const auto back = gradients::mixed_photon_shift(s.b, d_off, d, r, fault);
    if ((back.b - b).norm() > 10.0f * tol) ++t.not_inverted;
  }
  return t;
}

}  // namespace

TEST_CASE("volume photon shift: the mixed shift is a bijection between the kernels", "[unit]") {
  const Tally t = run(PhotonShiftFault::none, 1);
  std::printf("[mixed shift] null %lld, simple %lld, reflected %lld; outside %lld, not inverted %lld of %lld\n",
              static_cast<long long>(t.count[0]), static_cast<long long>(t.count[1]), static_cast<long long>(t.count[2]),
              static_cast<long long>(t.outside), static_cast<long long>(t.not_inverted), static_cast<long long>(t.n));
  CHECK(t.count[int(PhotonShiftKind::null)] > 1000);
  CHECK(t.count[int(PhotonShiftKind::simple)] > 1000);
  CHECK(t.count[int(PhotonShiftKind::reflected)] > 1000);
  CHECK(t.outside == 0);
  CHECK(t.not_inverted == 0);
  // The defect: reflection without its factor 2 (projects onto the plane).
  const Tally bad = run(PhotonShiftFault::half_reflection, 1);
  std::printf("[mixed shift, half reflection] outside %lld, not inverted %lld\n", static_cast<long long>(bad.outside),
              static_cast<long long>(bad.not_inverted));
  CHECK(bad.not_inverted > 1000);
}

TEST_CASE("volume photon shift: the mixed shift's Jacobian is 1", "[unit]") {
  core::Rng rng(2, 0);
  int tested[3] = {0, 0, 0};
  for (int k = 0; k < 3000; ++k) {
    const float r = 0.5f;
    const Vec3 d = in_ball(rng, Vec3::Zero(), 1.0f);
    const Vec3 d_off = d + in_ball(rng, Vec3::Zero(), 1.0f).normalized() * (r * (0.1f + 1.5f * rng.uniform()));
    const Vec3 b = in_ball(rng, d, 0.95f * r);
    const auto s = gradients::mixed_photon_shift(b, d, d_off, r);
    // Central differences in double precision of a float map: step 1e-3 r.
    const float h = 1e-3f * r;
    Eigen::Matrix3d jac;
    bool same_branch = true;
    for (int a = 0; a < 3; ++a) {
      Vec3 e = Vec3::Zero();
      e[a] = h;
      const auto p = gradients::mixed_photon_shift(b + e, d, d_off, r), m = gradients::mixed_photon_shift(b - e, d, d_off, r);
      same_branch = same_branch && p.kind == s.kind && m.kind == s.kind;
      jac.col(a) = ((p.b - m.b).cast<double>()) / (2.0 * double(h));
    }
    if (!same_branch) continue;
    ++tested[int(s.kind)];
    CHECK(std::abs(std::abs(jac.determinant()) - 1.0) < 2e-3);
  }
  CHECK(tested[0] > 100);
  CHECK(tested[1] > 100);
  CHECK(tested[2] > 100);
}

TEST_CASE("volume photon shift: the gather distance is copied within the offset segment", "[unit]") {
  float t = 0;
  CHECK(gradients::shift_gather_distance(0.3f, 0.5f, t));
  CHECK(t == 0.3f);
  CHECK_FALSE(gradients::shift_gather_distance(0.6f, 0.5f, t));
  CHECK(gradients::shift_gather_distance(2.0f, kInfinity, t));
}
