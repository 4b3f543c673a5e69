// Per-sample physics of gradient-domain bidirectional path tracing (Manzi et al. 2015):
// one BDPT sample (a camera subpath through a jittered position of pixel i and one light
// subpath, every strategy (s, t) connected; pathspace/bidir_*), and for each of the four
// neighbours j the offset of every strategy's path under the G-BDPT shift
// (gradients/bidir_shift.h): the camera subpath is shifted once per neighbour and serves
// every camera strategy; a light-tracing path (t = 1) is shifted by its own primary ray.
//  * primal (`primal=pairs`, default, as G-PT): each pair's estimates of both pixels,
//    primal_i += 1/4 w f(x)/p_st(x), primal_j += 1/4 w f(T x)|T'|/p_st(x) per neighbour
//    (the four pairs' weights w and the neighbours' ones sum to 1 for every path; a pair
//    that is not formed leaves w_bal(x) f(x)/p_st(x) to pixel i); `primal=bdpt`: the BDPT
//    estimate w_st f(x)/p_st(x) with the `mis` heuristic (Manzi 2015's primal). Light
//    tracing's pixel is where x_1 projects. Paths of one segment (a light seen directly)
//    go to `direct` only and are never shifted (ALGORITHMS.md).
//  * gradient(i -> j) += w (f(T x)|T'| - f(x)) / p_st(x) with the balance heuristic over
//    both pixels' strategies, w = p_st(x) / sum_r (p_r(x) + p_r(T x)|T'|) (Manzi 2015,
//    Eq. 6; computed as 1 / (1/w_bal(x) + R / w_bal(T x)), R = p_st(T x)|T'| / p_st(x)).
//    A failed shift or an offset of zero value is the T_0 fallback: -w_bal(x) f(x)/p_st(x)
//    (the failure is a property of the pair, symmetric in x and T x, so the fallback and
//    the pair terms together stay unbiased). Stored as dx / dy of the forward pair; a pair
//    whose neighbour lies outside the image is not estimated.
// A sample with any non-finite value is dropped whole and counted.
#pragma once

#include <array>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/bidir_shift.h"
#include "gradients/gradient_buffers.h"
#include "integrators/pair_splats.h"
#include "integrators/gbdpt/gbdpt_settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats once per tile.
struct GbdptCounters {
  int64_t samples = 0, nan_dropped = 0, connections = 0, occluded = 0;
  int64_t camera_shifts = 0, camera_rejoined = 0, light_shifts = 0, light_shifted = 0;
  int64_t camera_chain = 0, light_chain = 0;  // a specular chain after b that cannot be walked
  manifold::WalkStats walks;                  // the chain walks b..c (forward and reverse)
  std::array<int64_t, gradients::kShiftStatusCount> camera_fail{}, light_fail{};
  int64_t pairs_shifted = 0, pairs_fallback = 0, outside_image = 0, direct = 0;
  void flush(core::Stats& stats) const;
};

// One base strategy with a non-zero contribution (path of >= 2 segments).
struct GbdptTerm {
  int s = 0, t = 0;
  int px = 0, py = 0;  // the base pixel (t = 1: where x_1 projects)
  Vec2 raster{0, 0};   // t = 1: the exact projection
  Rgb value = Rgb::Zero();  // f(x) / p_st(x)
  double w_bal = 0;         // balance-heuristic BDPT weight of (s, t) for x
  pathspace::ReversePdfs reverse;  // the connection's reverse densities (shared by offsets that keep them)
};

// Per-thread scratch (no allocation per sample once warmed up).
struct GbdptScratch {
  std::vector<pathspace::BidirVertex> camera, light;
  Vec2 camera_raster{0, 0};  // where the camera subpath's primary ray goes through
  std::vector<GbdptTerm> terms;
  gradients::CameraSubpathShift shift;
  gradients::LightTracingShift lt;
  PairSplats splats;  // what the sample adds (flushed whole or dropped)
};

class GbdptTracer {
 public:
  GbdptTracer(const scene::Scene& scene, const GbdptSettings& settings, int max_depth);
  // One base sample in pixel (px, py) with its four neighbours' offsets.
  void sample(int px, int py, core::Rng& rng, GbdptScratch& scratch, gradients::GradientBuffers& buf,
              GbdptCounters& counters) const;

 private:
  void offsets(int nb, GbdptScratch& sc, int w, int h, GbdptCounters& counters) const;
  const scene::Scene& m_scene;
  GbdptSettings m_settings;
  int m_max_depth;
  pathspace::MisConfig m_balance, m_unweighted;
  bool m_pair_primal = true;
  gradients::BidirShiftOptions m_shift;
};

}  // namespace dp::integrators
