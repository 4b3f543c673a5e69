#include "kernels_adaptive/affinity.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace dp::kernels_adaptive {

namespace {

// Manzi et al. 2014, Eq. 7 exponent for one feature: max(0, d2 - tau) / sigma^2.
double excess(double d2, double tau, double sigma) { return std::max(0.0, d2 - tau) / (sigma * sigma); }

template <typename V>
double squared_distance(const V& a, const V& b) {
  double d2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = double(a[c]) - double(b[c]);
    d2 += d * d;
  }
  return d2;
}

}  // namespace

void validate(const AffinityParams& p) {
  const float sigmas[3] = {p.sigma_normal, p.sigma_texture, p.sigma_depth};
  const float taus[3] = {p.tau_normal, p.tau_texture, p.tau_depth};
  for (int k = 0; k < 3; ++k) {
    if (!(std::isfinite(sigmas[k]) && sigmas[k] > 0.0f))
      throw ValueError("kernels_adaptive: affinity sigma must be finite and > 0");
    if (!(std::isfinite(taus[k]) && taus[k] >= 0.0f))
      throw ValueError("kernels_adaptive: affinity tau must be finite and >= 0");
  }
  if (p.window < 3 || p.window % 2 == 0)
    throw ValueError("kernels_adaptive: affinity window must be odd and >= 3, got " + std::to_string(p.window));
  if (p.neighbours < 1)
    throw ValueError("kernels_adaptive: need at least one neighbour per pixel, got " + std::to_string(p.neighbours));
}

double feature_affinity(double d2, double tau, double sigma) { return std::exp(-excess(d2, tau, sigma)); }

double affinity_cost(const Features& f, int32_t i, int32_t j, const AffinityParams& p) {
  const size_t a = size_t(i), b = size_t(j);
  // omega = min_k omega_k  <=>  cost = max_k cost_k (Eq. 7: the least similar feature).
  const double normal = excess(squared_distance(f.normal[a], f.normal[b]), p.tau_normal, p.sigma_normal);
  const double texture = excess(squared_distance(f.albedo[a], f.albedo[b]), p.tau_texture, p.sigma_texture);
  const double dd = double(f.depth[a]) - double(f.depth[b]);
  const double depth = excess(dd * dd, p.tau_depth, p.sigma_depth);
  return std::max({normal, texture, depth});
}

double affinity(const Features& f, int32_t i, int32_t j, const AffinityParams& p) {
  return std::exp(-affinity_cost(f, i, j, p));
}

std::vector<int32_t> most_similar(const Features& f, int32_t i, const AffinityParams& p) {
  struct Candidate {
    double cost;
    int dist2;
    int32_t j;
  };
  const int w = f.width, h = f.height, r = p.window / 2;
  const int xi = int(i % w), yi = int(i / w);
  std::vector<Candidate> cands;
  cands.reserve(size_t(p.window) * size_t(p.window));
  for (int y = std::max(0, yi - r); y <= std::min(h - 1, yi + r); ++y)
    for (int x = std::max(0, xi - r); x <= std::min(w - 1, xi + r); ++x) {
      if (x == xi && y == yi) continue;
      const int32_t j = int32_t(y * w + x);
      cands.push_back({affinity_cost(f, i, j, p), (x - xi) * (x - xi) + (y - yi) * (y - yi), j});
    }
  const size_t n = std::min(cands.size(), size_t(p.neighbours));
  std::partial_sort(cands.begin(), cands.begin() + std::ptrdiff_t(n), cands.end(),
                    [](const Candidate& a, const Candidate& b) {
                      if (a.cost != b.cost) return a.cost < b.cost;
                      if (a.dist2 != b.dist2) return a.dist2 < b.dist2;
                      return a.j < b.j;
                    });
  std::vector<int32_t> out(n);
  for (size_t k = 0; k < n; ++k) out[k] = cands[k].j;
  return out;
}

}  // namespace dp::kernels_adaptive
