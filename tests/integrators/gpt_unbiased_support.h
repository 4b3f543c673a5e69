// Helpers of the G-PT unbiasedness tests (test_gpt_unbiased.cpp, test_gpt_manifold.cpp,
// test_gpt_glossy.cpp): per-block gradient sums of independent renders and Welch t-tests
// against PT; a render driven straight through GptTracer so that a test can run the
// real estimator with a deliberate defect (GptSettings::faults) through the same test.
#pragma once

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "gradients/gradient_buffers.h"
#include "integrators/gpt/gpt_tracer.h"
#include "integrators/integrator.h"
#include "pathspace/sample_stream.h"
#include "reconstruct/problem.h"
#include "reconstruct/solve.h"

#include "tests/support/quiet_options.h"
#include "tests/support/welch.h"

namespace dp::test {
constexpr int kRes = 16, kBlock = 4, kRuns = 10;

// One quiet 2-thread render with integrator settings `set` (key, value).
inline integrators::RenderResult render_with(const scene::Scene& s, const std::string& integrator, int spp,
                                             uint64_t seed, int max_depth,
                                             const std::vector<std::pair<std::string, std::string>>& set = {}) {
  integrators::Settings settings;
  for (const auto& kv : set) settings.set(kv.first, kv.second);
  auto in = integrators::make_integrator(integrator, settings);
  return in->render(s, quiet_options(spp, seed, max_depth));
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

// Appends one run to `out`: `img` is PT's image or G-PT's direct layer, dx / dy G-PT's
// gradient layers (null for PT), `mean_of` the image whose mean is tested (PT's image or
// G-PT's L2 reconstruction).
inline void add_run(Blocks& out, const core::Image& img, const core::Image* dx, const core::Image* dy,
                    const core::Image& mean_of) {
  const int nb = kRes / kBlock;
  out.grad.resize(size_t(2 * nb * nb));
  out.direct.resize(size_t(2 * nb * nb));
  auto px = [&](int x, int y) { return double(img(x, y).sum()); };
  for (int by = 0; by < nb; ++by)
    for (int bx = 0; bx < nb; ++bx) {
      double sx = 0, sy = 0, gx = 0, gy = 0;
      for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
        for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
          if (x + 1 < kRes) {
            sx += px(x + 1, y) - px(x, y);
            if (dx) gx += double((*dx)(x, y).sum());
          }
          if (y + 1 < kRes) {
            sy += px(x, y + 1) - px(x, y);
            if (dy) gy += double((*dy)(x, y).sum());
          }
        }
      out.direct[size_t(by * nb + bx)].push_back(sx);
      out.direct[size_t(nb * nb + by * nb + bx)].push_back(sy);
      out.grad[size_t(by * nb + bx)].push_back(gx);
      out.grad[size_t(nb * nb + by * nb + bx)].push_back(gy);
    }
  out.mean.push_back(mean_of.mean().sum());
}

// kRuns renders of `in` (seeds seed0, seed0 + 1, ...); `gradient`: a gradient-domain
// integrator (layers direct, dx, dy, recon_l2 as `gpt`).
inline Blocks stats_of(const scene::Scene& s, integrators::Integrator& in, bool gradient, int spp, uint64_t seed0,
                       int max_depth = 5) {
  Blocks out;
  for (int r = 0; r < kRuns; ++r) {
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed0 + uint64_t(r);
    opt.threads = 2;
    opt.max_depth = max_depth;
    opt.quiet = true;
    const auto res = in.render(s, opt);
    // PT: differences of the image (all in `direct`); G-PT: its gradient layers plus the
    // differences of its direct layer.
    if (gradient)
      add_run(out, layer(res, "direct"), &layer(res, "dx"), &layer(res, "dy"), layer(res, "recon_l2"));
    else
      add_run(out, res.layers[0].image, nullptr, nullptr, res.layers[0].image);
  }
  return out;
}

// `set`: integrator settings (key, value), e.g. {{"shift", "manifold"}}.
inline Blocks stats(const scene::Scene& s, const std::string& integrator, int spp, uint64_t seed0,
                    const std::vector<std::pair<std::string, std::string>>& set = {}, int max_depth = 5) {
  integrators::Settings settings;
  for (const auto& kv : set) settings.set(kv.first, kv.second);
  auto in = integrators::make_integrator(integrator, settings);
  const bool gradient = integrator == "gpt" || integrator == "gbdpt" || integrator == "gpm" || integrator == "gvcm";
  return stats_of(s, *in, gradient, spp, seed0, max_depth);
}

// GptSettings as `--integrator gpt` would read them from `set` (GptSettings' member
// defaults are not all the integrator's: read() applies e.g. the 0.05 shift threshold).
inline integrators::GptSettings gpt_settings(const std::vector<std::pair<std::string, std::string>>& set = {}) {
  integrators::Settings settings;
  for (const auto& kv : set) settings.set(kv.first, kv.second);
  const integrators::GptSettings g = integrators::GptSettings::read(settings);
  settings.check_all_used("gpt");
  return g;
}

// The layers of one gradient-domain render (G-PT, G-BDPT) that the tests use.
struct GptFrame {
  core::Image dx, dy, direct, l2;
};

// One gradient-domain render straight through a tracer (the per-sample physics of an
// integrator) with explicit settings, so a test can set its deliberate defects, which no
// scene key or --set reaches: `spp` samples in every pixel from the pixel's own random
// stream (seed, pixel), one thread, each by sample(x, y, rng, buffers); the integrators'
// per-pixel normalisation (GradientBuffers) and screened Poisson L2 solve with the direct
// layer added back (Lehtinen 2013, Eq. 8; Kettunen 2015, Sec. 6; as gpt_integrator.cpp).
template <class SampleFn>
GptFrame render_frame(const scene::Scene& s, int spp, uint64_t seed, float alpha, SampleFn&& sample) {
  const int w = s.camera().width(), h = s.camera().height();
  gradients::GradientBuffers buf(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      core::Rng rng(seed, uint64_t(y) * uint64_t(w) + uint64_t(x));
      for (int i = 0; i < spp; ++i) sample(x, y, rng, buf);
    }
  GptFrame f{buf.dx(), buf.dy(), buf.direct(), {}};
  const reconstruct::Problem problem = reconstruct::make_grid_problem(buf.primal(), f.dx, f.dy, alpha);
  reconstruct::SolveOptions sopt;
  sopt.threads = 1;
  f.l2 = reconstruct::solve_l2(problem, sopt).image;
  f.l2 += f.direct;
  return f;
}

// One G-PT render through GptTracer (render_frame).
inline GptFrame render_gpt_tracer(const scene::Scene& s, const integrators::GptSettings& settings, int spp,
                                  uint64_t seed, int max_depth) {
  const integrators::GptTracer tracer(s, settings, max_depth);
  integrators::GptCounters counters;
  return render_frame(s, spp, seed, settings.alpha,
                      [&](int x, int y, core::Rng& rng, gradients::GradientBuffers& buf) {
                        pathspace::IndependentStream stream(rng);
                        tracer.sample(x, y, stream, buf, counters);
                      });
}

// Blocks of kRuns renders render(seed0 + run) -> GptFrame, two runs at a time (they are
// independent).
template <class RenderFn>
Blocks frame_stats(uint64_t seed0, RenderFn&& render) {
  std::vector<GptFrame> frames(static_cast<size_t>(kRuns));
  auto run = [&](int first) {
    for (int r = first; r < kRuns; r += 2) frames[size_t(r)] = render(seed0 + uint64_t(r));
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  Blocks out;
  for (const GptFrame& f : frames) add_run(out, f.direct, &f.dx, &f.dy, f.l2);
  return out;
}

// stats() of kRuns renders through render_gpt_tracer (seeds seed0 + run).
inline Blocks tracer_stats(const scene::Scene& s, const integrators::GptSettings& settings, int spp, uint64_t seed0,
                           int max_depth = 5) {
  return frame_stats(seed0, [&](uint64_t seed) { return render_gpt_tracer(s, settings, spp, seed, max_depth); });
}

// Welch's t-test of mean(a) = mean(b) at 1% significance, Sidak-corrected over `tests`:
// t, its critical value and the standard error of the difference of the means (so a shift
// of the difference by more than crit * se is rejected about half the time, by more than
// (crit + 1.28) se about 90% of the time).
struct Welch {
  double t = 0, crit = 0, se = 0;
};
inline Welch welch(const std::vector<double>& a, const std::vector<double>& b, double scale_a, int tests) {
  Moments ma = moments(a), mb = moments(b);
  ma.mean *= scale_a;
  ma.var *= scale_a * scale_a;
  const double va = ma.var / double(a.size()), vb = mb.var / double(b.size());
  if (va + vb <= 0) return {};
  const double dof = (va + vb) * (va + vb) / (va * va / double(a.size() - 1) + vb * vb / double(b.size() - 1));
  const double alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(tests));
  Welch out;
  out.se = std::sqrt(va + vb);
  out.t = (ma.mean - mb.mean) / out.se;
  out.crit = boost::math::quantile(boost::math::complement(boost::math::students_t(dof), alpha / 2));
  return out;
}

// |t| / critical (Welch, Sidak over `tests`); < 1 passes.
inline double ratio(const std::vector<double>& a, const std::vector<double>& b, double scale_a, int tests, double* z) {
  const Welch wt = welch(a, b, scale_a, tests);
  if (!(wt.crit > 0)) return 0;
  if (z) *z = wt.t;
  return std::abs(wt.t) / wt.crit;
}

// The whole unbiasedness test of G-PT runs `g` against PT runs `p`: per-block Welch tests
// of the gradients (G-PT's gradient layers plus its direct layer's differences vs PT's
// differences; Sidak over the blocks) and one of the L2 reconstruction's mean against
// PT's image mean. It rejects if either ratio |t|/crit reaches 1.
struct Verdict {
  double grad = 0, zmax = 0;  // worst |t|/crit over gradient blocks and its |t|
  int worst_block = -1;
  double l2 = 0, zl2 = 0;     // L2 mean: |t|/crit and t
  // Power: the smallest relative error that moves some statistic by its critical value
  // (detected ~50% of the time; the *90 fields: ~90%, at (crit + 1.28) se). grad_scale: a
  // factor (1 + e) on every gradient, e = min over blocks of crit se / |G-PT block mean|;
  // l2_shift: a relative shift of the L2 mean, crit se / PT's mean.
  double grad_scale = 0, l2_shift = 0;
  double grad_scale90 = 0, l2_shift90 = 0;  // the same at ~90% power ((crit + 1.28) se)
  bool rejects() const { return grad >= 1.0 || l2 >= 1.0; }
};
inline Verdict verdict(const Blocks& g, const Blocks& p) {
  Verdict v;
  const int tests = int(g.grad.size());
  v.grad_scale = v.grad_scale90 = 1e300;
  for (int i = 0; i < tests; ++i) {
    const std::vector<double> gi = g.scaled(size_t(i), 1.0);
    const Welch wt = welch(gi, p.direct[size_t(i)], 1.0, tests);
    if (!(wt.crit > 0)) continue;
    const double r = std::abs(wt.t) / wt.crit;
    if (r > v.grad) v.grad = r, v.zmax = std::abs(wt.t), v.worst_block = i;
    const double m = std::abs(moments(g.grad[size_t(i)]).mean);
    if (m > 0) v.grad_scale = std::min(v.grad_scale, wt.crit * wt.se / m);
    if (m > 0) v.grad_scale90 = std::min(v.grad_scale90, (wt.crit + 1.28) * wt.se / m);
  }
  const Welch wl = welch(g.mean, p.mean, 1.0, 1);
  v.l2 = wl.crit > 0 ? std::abs(wl.t) / wl.crit : 0;
  v.zl2 = wl.t;
  v.l2_shift = wl.crit * wl.se / std::abs(moments(p.mean).mean);
  v.l2_shift90 = (wl.crit + 1.28) * wl.se / std::abs(moments(p.mean).mean);
  return v;
}
}  // namespace dp::test
