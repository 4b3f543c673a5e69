// Manifold-walk cost and success rates: random specular chains of 1-6 vertices in a
// mirror box with a glass and a mirror sphere (the stress scene of tests/manifold),
// ideal specular and glossy (alpha 0.2) targets, end moved by 1% and 10% of the box.
// Output: CSV on stdout (len, alpha, radius, walks, converged, mean_iters, us_per_walk).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "tests/manifold/manifold_fixtures.h"

using namespace dp;
using namespace dp::test_mf;

int main() {
  Builder b;
  b.quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, std::nullopt);
  b.quad({1, -1, 0}, {1, 1, 0}, {1, 1, 2}, {1, -1, 2}, Material{});
  b.quad({-1, -1, 0}, {-1, -1, 2}, {-1, 1, 2}, {-1, 1, 0}, Material{});
  b.quad({-1, 1, 0}, {-1, 1, 2}, {1, 1, 2}, {1, 1, 0}, Material{});
  b.quad({-1, -1, 0}, {1, -1, 0}, {1, -1, 2}, {-1, -1, 2}, Material{});
  b.sphere({0.1f, 0.05f, 0.6f}, 0.3f, Material{Interaction::refraction, 1.5});
  b.sphere({0.5f, -0.45f, 0.35f}, 0.2f, Material{});
  const auto spec = b.specular;
  auto scene = b.commit();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  std::printf("len,alpha,radius,walks,converged,mean_iters,us_per_walk\n");
  for (int len = 1; len <= 6; ++len)
    for (double alpha : {0.0, 0.2}) {
      std::vector<Chain> chains;
      while (chains.size() < 400) {
        const Vec3d x0(-0.6 + 1.2 * U(rng), -0.6 + 1.2 * U(rng), 1.7);
        const double phi = 2 * kPiD * U(rng), ct = -(0.2 + 0.8 * U(rng)), st = std::sqrt(1 - ct * ct);
        auto c = trace_chain(*scene, spec, make_point(x0), Vec3d(st * std::cos(phi), st * std::sin(phi), ct), len,
                             [&](int) {
                               Vec2d t(alpha * N(rng), alpha * N(rng));
                               return t.norm() < 0.7 ? t : Vec2d(0, 0);
                             });
        if (c) chains.push_back(*c);
      }
      for (double radius : {0.01, 0.1}) {
        WalkStats stats;
        const auto t0 = std::chrono::steady_clock::now();
        for (const Chain& c : chains) {
          const ChainVertex& e = c.v.back();
          const double a = 2 * kPiD * U(rng);
          Vec3d target = e.p() + radius * (std::cos(a) * e.f.T1 + std::sin(a) * e.f.T2);
          target.x() = std::clamp(target.x(), -0.999, 0.999);
          target.y() = std::clamp(target.y(), -0.999, 0.999);
          walk(*scene, c, target, WalkSettings{}, &stats);
        }
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
        std::printf("%d,%.2f,%.2f,%lld,%lld,%.2f,%.2f\n", len, alpha, radius, (long long)stats.attempted,
                    (long long)stats.converged, stats.mean_iterations(), us / double(stats.attempted));
      }
    }
  return 0;
}
