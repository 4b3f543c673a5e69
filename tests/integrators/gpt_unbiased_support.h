// Helpers of the G-PT unbiasedness tests (test_gpt_unbiased.cpp, test_gpt_manifold.cpp):
// per-block gradient sums of independent renders and Welch t-tests against PT.
#pragma once

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.h"

namespace dp::test {
constexpr int kRes = 16, kBlock = 4, kRuns = 10;

// One quiet 2-thread render with integrator settings `set` (key, value).
inline integrators::RenderResult render_with(const scene::Scene& s, const std::string& integrator, int spp,
                                             uint64_t seed, int max_depth,
                                             const std::vector<std::pair<std::string, std::string>>& set = {}) {
  integrators::Settings settings;
  for (const auto& kv : set) settings.set(kv.first, kv.second);
  auto in = integrators::make_integrator(integrator, settings);
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = max_depth;
  opt.quiet = true;
  return in->render(s, opt);
}

inline const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  return r.layers[0].image;
}

// Per run and block: the sum of forward differences over the block (dx blocks, then dy
// blocks), split for G-PT into its gradient layers' part (`grad`) and its direct layer's
// part (`direct`: emitters seen from the camera are kept out of the gradients; their
// differences are PT's depth-1 term), plus the image mean (L2 for G-PT).
struct Blocks {
  std::vector<std::vector<double>> grad, direct;
  std::vector<double> mean;
  // One run of every block with the gradient part scaled (a x2 / x0.5 splat error).
  std::vector<double> scaled(size_t block, double s) const {
    std::vector<double> v(grad[block].size());
    for (size_t r = 0; r < v.size(); ++r) v[r] = s * grad[block][r] + direct[block][r];
    return v;
  }
};

// `set`: integrator settings (key, value), e.g. {{"shift", "manifold"}}.
inline Blocks stats(const scene::Scene& s, const std::string& integrator, int spp, uint64_t seed0,
                    const std::vector<std::pair<std::string, std::string>>& set = {}, int max_depth = 5) {
  integrators::Settings settings;
  for (const auto& kv : set) settings.set(kv.first, kv.second);
  auto in = integrators::make_integrator(integrator, settings);
  const int nb = kRes / kBlock;
  Blocks out;
  out.grad.resize(size_t(2 * nb * nb));
  out.direct.resize(size_t(2 * nb * nb));
  for (int r = 0; r < kRuns; ++r) {
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed0 + uint64_t(r);
    opt.threads = 2;
    opt.max_depth = max_depth;
    opt.quiet = true;
    const auto res = in->render(s, opt);
    const bool gpt = integrator == "gpt";
    // PT: differences of the image (all in `direct`); G-PT: its gradient layers plus the
    // differences of its direct layer.
    const core::Image& img = gpt ? layer(res, "direct") : res.layers[0].image;
    auto px = [&](int x, int y) { return double(img(x, y).sum()); };
    for (int by = 0; by < nb; ++by)
      for (int bx = 0; bx < nb; ++bx) {
        double sx = 0, sy = 0, gx = 0, gy = 0;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
            if (x + 1 < kRes) {
              sx += px(x + 1, y) - px(x, y);
              if (gpt) gx += double(layer(res, "dx")(x, y).sum());
            }
            if (y + 1 < kRes) {
              sy += px(x, y + 1) - px(x, y);
              if (gpt) gy += double(layer(res, "dy")(x, y).sum());
            }
          }
        out.direct[size_t(by * nb + bx)].push_back(sx);
        out.direct[size_t(nb * nb + by * nb + bx)].push_back(sy);
        out.grad[size_t(by * nb + bx)].push_back(gx);
        out.grad[size_t(nb * nb + by * nb + bx)].push_back(gy);
      }
    out.mean.push_back((gpt ? layer(res, "recon_l2") : res.layers[0].image).mean().sum());
  }
  return out;
}

struct Moments {
  double mean, var;
};
inline Moments moments(const std::vector<double>& v) {
  double m = 0, s2 = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  for (double x : v) s2 += (x - m) * (x - m);
  return {m, s2 / double(v.size() - 1)};
}
// |t| / critical (Welch, Sidak over `tests`); < 1 passes.
inline double ratio(const std::vector<double>& a, const std::vector<double>& b, double scale_a, int tests, double* z) {
  Moments ma = moments(a), mb = moments(b);
  ma.mean *= scale_a;
  ma.var *= scale_a * scale_a;
  const double va = ma.var / double(a.size()), vb = mb.var / double(b.size());
  if (va + vb <= 0) return 0;
  const double t = (ma.mean - mb.mean) / std::sqrt(va + vb);
  const double dof = (va + vb) * (va + vb) / (va * va / double(a.size() - 1) + vb * vb / double(b.size() - 1));
  const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(tests));
  const double crit = boost::math::quantile(boost::math::complement(boost::math::students_t(dof), alpha / 2));
  if (z) *z = t;
  return std::abs(t) / crit;
}
}  // namespace dp::test
