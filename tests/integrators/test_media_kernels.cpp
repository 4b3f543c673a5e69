// Kernels and queries of the volumetric photon density estimators (issue 15; `vpm`,
// `bre`, integrators/media_photons):
//  * the uniform 3D and 2D kernels integrate to 1 (Monte Carlo over their bounding cube
//    or square, z-test);
//  * the progressive radius equals the recursion r_{i+1}^D = r_i^D (i + a) / (i + 1)
//    and decays as i^((a - 1) / D);
//  * the photon BVH's point and beam queries return exactly the brute-force sets;
//  * estimator normalization: over a uniform photon field of density rho, a point query
//    weighted by K3 estimates rho and a beam query of length l weighted by K2 estimates
//    rho l (z-tests from the Poisson count variance); the same tests reject the other
//    dimension's kernel (the defects VpmFault::kernel_2d_norm / BreFault::kernel_3d_norm);
//    the Point-Beam 3D estimate (bre kernel=3d, gbre: each photon within r of the beam
//    weighted by its chord's length and K3, from the query widened by r at both ends)
//    estimates rho l too, and rejects the 2D normalization and the unwidened query;
//  * vpm's truncated-exponential gather distances (Gruson et al. 2018, Eq. 14) follow
//    their pdf (chi-square) and the pdf integrates to 1 over the segment.
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "integrators/media_photons/photon_bvh.h"
#include "integrators/media_photons/volume_kernel.h"
#include "integrators/vpm/vpm_gather.h"

using namespace dp;
using integrators::MediumPhoton;

namespace {

double z_crit(double alpha) { return boost::math::quantile(boost::math::normal(), 1.0 - alpha / 2.0); }

std::vector<MediumPhoton> uniform_photons(int n, float side, uint64_t seed) {
  core::Rng rng(seed, 1);
  std::vector<MediumPhoton> out(static_cast<size_t>(n));
  for (auto& p : out) {
    p.p = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * side;
    p.beta = Rgb::Ones();
    p.depth = 1;
    p.medium = 0;
  }
  return out;
}

}  // namespace

TEST_CASE("media kernels: the uniform 3D and 2D kernels integrate to one", "[unit]") {
  core::Rng rng(5, 0);
  const double r = 0.37;
  for (int dim : {2, 3}) {
    // Uniform points in [-r, r]^dim: estimate of int K = (2r)^dim K(r) P(inside).
    constexpr int kN = 200000;
    double s = 0, s2 = 0;
    for (int i = 0; i < kN; ++i) {
      double q = 0;
      for (int k = 0; k < dim; ++k) {
        const double x = (2.0 * double(rng.uniform()) - 1.0) * r;
        q += x * x;
      }
      const double v = q <= r * r ? std::pow(2.0 * r, dim) * integrators::uniform_kernel(dim, r) : 0.0;
      s += v;
      s2 += v * v;
    }
    const double mean = s / kN, se = std::sqrt((s2 / kN - mean * mean) / kN);
    std::printf("[kernel %dD] integral %.4f +- %.4f\n", dim, mean, se);
    CHECK(std::abs(mean - 1.0) < z_crit(1e-3) * se);
    // The other dimension's normalization is far off (r != 1 on purpose).
    const double wrong = mean * integrators::uniform_kernel(5 - dim, r) / integrators::uniform_kernel(dim, r);
    CHECK(std::abs(wrong - 1.0) > z_crit(1e-3) * se);
  }
}

TEST_CASE("media kernels: the progressive radius follows Knaus & Zwicker's recursion", "[unit]") {
  for (int dim : {2, 3})
    for (double alpha : {0.5, 0.7, 1.0}) {
      double rd = 1.0;  // r_i^dim, recursively
      for (int64_t i = 0; i < 200; ++i) {
        const double r = integrators::progressive_radius(2.0, i, alpha, dim);
        CHECK(r == Approx(2.0 * std::pow(rd, 1.0 / dim)).epsilon(1e-9));
        rd *= (double(i + 1) + alpha) / double(i + 2);
      }
      // r_i ~ c i^((alpha - 1) / dim): the ratio of r at i and 2i tends to 2^((alpha-1)/dim).
      const double a = integrators::progressive_radius(1.0, 100000, alpha, dim);
      const double b = integrators::progressive_radius(1.0, 200001, alpha, dim);
      CHECK(b / a == Approx(std::pow(2.0, (alpha - 1.0) / dim)).epsilon(1e-4));
    }
}

TEST_CASE("media kernels: photon BVH queries return the brute-force sets", "[unit]") {
  const auto photons = uniform_photons(5000, 2.0f, 3);
  integrators::PhotonBvh bvh;
  bvh.build(photons);
  REQUIRE(bvh.size() == photons.size());
  core::Rng rng(8, 0);
  int64_t found = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 c = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.4f - Vec3::Constant(0.2f);
    const float r = 0.05f + 0.3f * rng.uniform();
    int64_t brute = 0, got = 0;
    for (const auto& p : photons) brute += (p.p - c).squaredNorm() <= r * r ? 1 : 0;
    bvh.query_point(c, r, [&](const MediumPhoton&, float) { ++got; });
    CHECK(got == brute);
    found += got;
    // Beams: random directions, every third axis-aligned (the slab test's 0 * inf case),
    // every fifth unbounded.
    Vec3 d = Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f).normalized();
    if (q % 3 == 0) d = Vec3::Unit(q % 9 / 3);
    const float tmax = q % 5 == 0 ? kInfinity : 3.0f * rng.uniform();
    brute = got = 0;
    for (const auto& p : photons) {
      const Vec3 v = p.p - c;
      const float t = v.dot(d);
      brute += t >= 0.0f && t <= tmax && v.squaredNorm() - t * t <= r * r ? 1 : 0;
    }
    bvh.query_beam(c, d, tmax, r, [&](const MediumPhoton&, float, float) { ++got; });
    CHECK(got == brute);
    found += got;
  }
  CHECK(found > 1000);  // the queries were not empty
}

TEST_CASE("media kernels: point and beam estimates of a uniform photon field are normalized", "[unit]") {
  // rho photons per unit volume in [0, 4]^3 (binomial counts, nearly Poisson); queries
  // well inside (no boundary effect) and disjoint (independent counts): balls of radius r
  // on a lattice of spacing 0.5, beams along x of length l on a lattice in y and z.
  constexpr int kPhotons = 200000, kFields = 4;
  const float side = 4.0f;
  const double rho = kPhotons / double(side * side * side);
  const double r = 0.2, len = 1.5;
  double point = 0, beam = 0, beam3 = 0, beam3_narrow = 0;
  int points = 0, beams = 0;
  for (int field = 0; field < kFields; ++field) {
    integrators::PhotonBvh bvh;
    bvh.build(uniform_photons(kPhotons, side, 40 + uint64_t(field)));
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        for (int k = 0; k < 5; ++k) {
          int n = 0;
          bvh.query_point(Vec3(1.0f + 0.5f * float(i), 1.0f + 0.5f * float(j), 1.0f + 0.5f * float(k)), float(r),
                          [&](const MediumPhoton&, float) { ++n; });
          point += n * integrators::uniform_kernel(3, r);
          ++points;
        }
        int m = 0;
        bvh.query_beam(Vec3(1.2f, 1.0f + 0.5f * float(i), 1.0f + 0.5f * float(j)), Vec3(1, 0, 0), float(len), float(r),
                       [&](const MediumPhoton&, float, float) { ++m; });
        beam += m * integrators::uniform_kernel(2, r);
        // Point-Beam 3D: sum of chord lengths x K3, over the query widened by r (and, the
        // defect, without widening: photons near the ends are missed).
        const Vec3 o(1.2f, 1.0f + 0.5f * float(i), 1.0f + 0.5f * float(j)), x(1, 0, 0);
        const float rf = float(r), lf = float(len);
        double chords = 0, narrow = 0;
        bvh.query_beam(o - rf * x, x, lf + 2.0f * rf, rf, [&](const MediumPhoton&, float t, float d2) {
          float lo = 0, hi = 0;
          if (integrators::point_beam_chord(t - rf, d2, rf, lf, lo, hi)) chords += double(hi - lo);
        });
        bvh.query_beam(o, x, lf, rf, [&](const MediumPhoton&, float t, float d2) {
          float lo = 0, hi = 0;
          if (integrators::point_beam_chord(t, d2, rf, lf, lo, hi)) narrow += double(hi - lo);
        });
        beam3 += chords * integrators::uniform_kernel(3, r);
        beam3_narrow += narrow * integrators::uniform_kernel(3, r);
        ++beams;
      }
  }
  point /= points;
  beam /= beams;
  beam3 /= beams;
  beam3_narrow /= beams;
  // A count n ~ Poisson(rho V): n K has mean rho (V K = 1) and variance rho K.
  const double se_point = std::sqrt(rho * integrators::uniform_kernel(3, r) / points);
  const double se_beam = std::sqrt(rho * len * integrators::uniform_kernel(2, r) / beams);
  std::printf("[normalization] point %.1f (rho %.1f +- %.1f), beam %.1f (rho l %.1f +- %.1f)\n", point, rho, se_point,
              beam, rho * len, se_beam);
  CHECK(std::abs(point - rho) < z_crit(1e-3) * se_point);
  CHECK(std::abs(beam - rho * len) < z_crit(1e-3) * se_beam);
  // Point-Beam 3D: the sum of chord x K3 over a Poisson field has mean rho int chord K3 dV
  // = rho l and variance rho K3^2 int chord^2 dV <= rho K3^2 (l + 2r) 2 pi r^4 (a full
  // chord 2 sqrt(r^2 - q^2) over the disk of radius r: 2 pi r^4; the ends clip it).
  const double k3 = integrators::uniform_kernel(3, r);
  const double se_beam3 = std::sqrt(rho * k3 * k3 * (len + 2 * r) * 2 * double(kPi) * std::pow(r, 4) / beams);
  std::printf("[normalization] point-beam 3D %.1f (rho l %.1f +- %.1f), unwidened query %.1f\n", beam3, rho * len,
              se_beam3, beam3_narrow);
  CHECK(std::abs(beam3 - rho * len) < z_crit(1e-3) * se_beam3);
  CHECK(std::abs(beam3_narrow - rho * len) > z_crit(1e-3) * se_beam3);
  const double beam3_2d = beam3 * integrators::uniform_kernel(2, r) / k3;
  CHECK(std::abs(beam3_2d - rho * len) > z_crit(1e-3) * se_beam3);
  // The defects: the point query with the 2D kernel, the beam query with the 3D kernel
  // (off by the factor 4 / (3 r) or its inverse).
  const double point_2d = point * integrators::uniform_kernel(2, r) / integrators::uniform_kernel(3, r);
  const double beam_3d = beam * integrators::uniform_kernel(3, r) / integrators::uniform_kernel(2, r);
  CHECK(std::abs(point_2d - rho) > z_crit(1e-3) * se_point);
  CHECK(std::abs(beam_3d - rho * len) > z_crit(1e-3) * se_beam);
}

TEST_CASE("media kernels: truncated-exponential gather distances follow their pdf", "[unit]") {
  struct Case {
    float sigma, s;
  };
  for (const Case c : {Case{2.0f, 0.8f}, Case{0.01f, 3.0f}, Case{0.0f, 2.0f}, Case{1.5f, kInfinity}}) {
    // pdf integrates to 1 (midpoint rule on [0, min(s, 30 / sigma)]).
    const float end = std::isfinite(c.s) ? c.s : 30.0f / c.sigma;
    double integral = 0;
    constexpr int kSteps = 20000;
    for (int i = 0; i < kSteps; ++i)
      integral += double(integrators::truncated_distance_pdf(c.sigma, c.s, (float(i) + 0.5f) * end / kSteps)) * double(end) / kSteps;
    CHECK(integral == Approx(1.0).epsilon(1e-3));
    // Chi-square of 20 equal-width cells against the pdf's cell probabilities.
    constexpr int kCells = 20, kN = 100000;
    std::vector<double> obs(kCells, 0.0);
    core::Rng rng(17, 0);
    for (int i = 0; i < kN; ++i) {
      const float t = integrators::sample_truncated_distance(c.sigma, c.s, rng.uniform());
      REQUIRE(t >= 0.0f);
      REQUIRE(t <= c.s);
      obs[size_t(std::min(kCells - 1, int(t / end * kCells)))] += 1.0;
    }
    double chi2 = 0;
    for (int k = 0; k < kCells; ++k) {
      double p = 0;
      for (int j = 0; j < 200; ++j)
        p += double(integrators::truncated_distance_pdf(c.sigma, c.s, (float(k) + (float(j) + 0.5f) / 200.0f) * end / kCells)) *
             double(end) / kCells / 200.0;
      if (k == kCells - 1 && !std::isfinite(c.s)) p = 1.0 - (1.0 - std::exp(-double(c.sigma) * double(end))) + p;
      const double e = p * kN;
      chi2 += (obs[size_t(k)] - e) * (obs[size_t(k)] - e) / e;
    }
    const double crit = boost::math::quantile(boost::math::chi_squared(kCells - 1), 1.0 - 1e-3);
    std::printf("[truncated distance] sigma %.2f s %.2f: chi2 %.1f (crit %.1f)\n", double(c.sigma), double(c.s), chi2, crit);
    CHECK(chi2 < crit);
  }
}
