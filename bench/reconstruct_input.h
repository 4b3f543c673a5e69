// The synthetic 1280x720 input of the reconstruction benchmarks (bench_reconstruct,
// bench_l1_phases): a smooth image with edges, primal noise sigma 0.2, gradient noise
// sigma 0.02, fixed seeds.
#pragma once

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "reconstruct/problem.h"

namespace dp::bench {

inline core::Image truth_image(int w, int h) {
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float u = float(x) / float(w), v = float(y) / float(h);
      Rgb c(0.2f + 0.5f * u, 0.3f + 0.4f * v * v, 0.5f + 0.3f * std::sin(12.0f * u + 5.0f * v));
      if ((x / 160 + y / 120) % 2) c += Rgb(0.5f, 0.2f, 0.1f);
      img(x, y) = c;
    }
  return img;
}

inline float gaussian(core::Rng& rng) {
  const double u1 = 1.0 - rng.uniform_double(), u2 = rng.uniform_double();
  return float(std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPiD * u2));
}

inline reconstruct::Problem noisy(const reconstruct::Kernel& k, const core::Image& truth, uint64_t seed) {
  reconstruct::Problem p;
  p.kernel = k;
  p.primal = truth;
  p.b = reconstruct::apply_kernel(k, truth);
  core::Rng rng(seed, 0);
  for (auto& v : p.primal.pixels()) v += 0.2f * Rgb(gaussian(rng), gaussian(rng), gaussian(rng));
  for (auto& v : p.b) v += 0.02f * Rgb(gaussian(rng), gaussian(rng), gaussian(rng));
  return p;
}

inline double rmse(const core::Image& a, const core::Image& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += double((a[i] - b[i]).matrix().squaredNorm());
  return std::sqrt(s / double(3 * a.size()));
}

}  // namespace dp::bench
