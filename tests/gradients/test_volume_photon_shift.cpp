// G-VPM's kernel-space shifts (Gruson et al. 2018, Sec. 4.1-4.2; gradients/volume_photon_shift.h):
//  * the mixed shift (Eq. 16) maps every photon of the base kernel into the offset kernel,
//    the mixed shift back from d' to d returns it (bijection), all three branches occur,
//    and its Jacobian determinant is 1 in magnitude (central differences away from the
//    branch boundaries); the reflection without its factor 2 is rejected by the same
//    checks (it leaves photons non-invertible);
//  * the gather-point shift copies the distance and fails past the offset segment's end;
//  * the reconnection of a shifted photon to its medium parent (volume_photon_reconnect.h):
//    f / p at the base photon equals the photon tracer's weight Tr sigma_s / p_ff, and the
//    shifted estimator E[f(b + D) g(b + D) / p(b)] equals the direct E[f(b) g(b) / p(b)]
//    (both are int f g dV; z-test per channel); dropping the volume factor 1 / t^2 is
//    rejected.
#include <boost/math/distributions/normal.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "gradients/volume_photon_reconnect.h"
#include "gradients/volume_photon_shift.h"
#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

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

namespace {

scene::HomogeneousMedium test_medium() {
  scene::HomogeneousMedium m;
  m.sigma_s = Rgb(0.8f, 1.2f, 1.6f);
  m.sigma_a = Rgb(0.2f, 0.1f, 0.3f);
  m.phase.type = scene::PhaseFunctionDesc::Type::hg;
  m.phase.g = 0.5f;
  return m;
}

// g: the indicator of a box away from the parent at the origin.
bool in_box(const Vec3& x) {
  return x.x() >= 0.5f && x.x() <= 1.5f && std::abs(x.y()) <= 0.5f && std::abs(x.z()) <= 0.5f;
}

// Largest |z| over channels of (shifted - direct) estimates of int f g dV.
double reconnect_z(gradients::ReconnectFault fault) {
  const auto m = test_medium();
  const gradients::MediumParent parent{Vec3::Zero(), Vec3(1.0f, 0.2f, 0.0f).normalized()};
  const Vec3 shift(0.3f, 0.2f, -0.1f);
  core::Rng rng(31, 0);
  constexpr int kN = 400000;
  double s1[3] = {0, 0, 0}, q1[3] = {0, 0, 0}, s2[3] = {0, 0, 0}, q2[3] = {0, 0, 0};
  double worst_weight = 0;
  for (int i = 0; i < 2 * kN; ++i) {
    const Vec3 w = scene::HenyeyGreenstein(m.phase).sample(parent.w_in, rng.uniform2());
    const float uc = rng.uniform(), u = rng.uniform();
    const scene::FreeFlightSample ff = scene::sample_free_flight(m, kInfinity, uc, u);
    const Vec3 b = parent.a + ff.t * w;
    const float p = gradients::photon_volume_pdf(parent, m, b, fault);
    if (!(p > 0.0f)) continue;
    if (i < kN) {  // the base photon's weight, f / p = Tr sigma_s / p_ff (photon_tracer.h)
      const Rgb ratio = gradients::photon_edge_throughput(parent, m, b, fault) / p;
      worst_weight = std::max(worst_weight, double(((ratio - ff.weight).abs() / ff.weight).maxCoeff()));
    }
    const bool second = i >= kN;
    const Vec3 y = second ? b : Vec3(b + shift);  // the direct or the shifted estimator
    if (!in_box(y)) continue;
    const Rgb v = gradients::photon_edge_throughput(parent, m, y, fault) / p;
    for (int c = 0; c < 3; ++c) {
      (second ? s2 : s1)[c] += double(v[c]);
      (second ? q2 : q1)[c] += double(v[c]) * double(v[c]);
    }
  }
  CHECK(worst_weight < 1e-4);
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    const double m1 = s1[c] / kN, m2 = s2[c] / kN;
    const double v1 = (q1[c] / kN - m1 * m1) / kN, v2 = (q2[c] / kN - m2 * m2) / kN;
    worst = std::max(worst, std::abs(m1 - m2) / std::sqrt(v1 + v2));
    std::printf("[reconnect fault %d] ch %d: shifted %.5f, direct %.5f\n", int(fault), c, m1, m2);
  }
  return worst;
}

}  // namespace

TEST_CASE("volume photon reconnect: a shifted photon reconnected to its medium parent is unbiased", "[unit]") {
  // 3 channels at 1e-3 family-wise, two-sided.
  const double z_crit = boost::math::quantile(boost::math::normal(), 1.0 - (1.0 - std::pow(1.0 - 1e-3, 1.0 / 3.0)) / 2.0);
  const double z = reconnect_z(gradients::ReconnectFault::none);
  const double z_bad = reconnect_z(gradients::ReconnectFault::no_volume_factor);
  std::printf("[reconnect] |z| %.2f, without the volume factor %.2f (crit %.2f)\n", z, z_bad, z_crit);
  CHECK(z < z_crit);
  CHECK(z_bad > z_crit);
}
