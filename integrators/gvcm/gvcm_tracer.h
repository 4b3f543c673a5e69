// Per-camera-sample physics of gradient-domain vertex connection and merging (Sun et al.
// 2017, Algorithm 1 lines 9-25). One camera subpath through a jittered position of pixel i
// and the iteration's light path i (integrators/vcm): every connection (s, t) as VCM's
// (light tracing, t = 1, evaluated here for light path i rather than in the light pass, so
// that its shift can use the camera) and every merge of a photon within r of a camera
// vertex, weighted by VCM's MIS (pathspace/vcm_mis.h, eta = pi r^2 N). For each neighbour j
// the camera subpath is shifted once (gradients/bidir_shift.h) and every term is shifted:
//  * connection t >= 2 and s = 0: the offset camera prefix with the same light subpath
//    (G-BDPT's map); t = 1: the light-tracing shift (the light subpath rejoined at y_1);
//  * merge at camera vertex z_k, case 1 (k >= join, the first vertex the offset shares):
//    the same photon at the same vertex, f from the offset's z_{k-1} and the offset
//    prefix's throughput (Eq. 16-17);
//  * merge at z_b, case 2: the merging shift (gradients/merge_shift.h, Eq. 18-20);
//  * a merge at a mixed vertex before b or inside a walked chain: no shift (T_0).
// Gradient weight (Eq. 21-23): the active strategies of x and the passive ones of T x,
//   w = p_s(x)^beta / (sum_r p_r(x)^beta + sum_r (p_r(Tx)|T'|)^beta) = 1 / (1/w(x) + R^beta / w(Tx)),
// w(x), w(Tx) VCM's weights (connections and merges, same heuristic) of base and offset for
// the strategy, R = p_s(Tx)|T'| / p_s(x) (the shift's MIS ratio; for case 2 the light
// side's area-density ratio toward z_b^off over toward the photon; one global radius).
// A failed shift is the T_0 fallback: -w(x) f(x)/p(x). Primal `pairs` as G-BDPT; paths of
// one segment go to `direct`, VCM-weighted, never shifted.
#pragma once

#include <array>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "integrators/pair_splats.h"
#include "gradients/merge_shift.h"
#include "integrators/gvcm/gvcm_settings.h"
#include "integrators/vcm/photon_grid.h"
#include "integrators/vcm/vcm_light_pass.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats once per tile.
struct GvcmCounters {
  int64_t samples = 0, nan_dropped = 0, connections = 0, occluded = 0, direct = 0;
  int64_t merge_queries = 0, merges = 0;
  int64_t camera_shifts = 0, camera_rejoined = 0, camera_chain = 0, light_shifts = 0, light_shifted = 0,
          light_chain = 0;
  int64_t merge_case1 = 0, merge_case2 = 0, merge_case2_shifted = 0, merge_chain = 0, merge_unshiftable = 0;
  std::array<int64_t, gradients::kShiftStatusCount> camera_fail{}, light_fail{}, merge_fail{};
  int64_t pairs_shifted = 0, pairs_fallback = 0, outside_image = 0;
  manifold::WalkStats walks;
  void flush(core::Stats& stats) const;
};

struct GvcmTerm {
  bool merge = false;
  int s = 0, t = 0;         // connection (s, t); merge: at camera[t - 1]
  int px = 0, py = 0;       // the base pixel (t = 1: where x_1 projects)
  Vec2 raster{0, 0};        // t = 1: the exact projection
  uint32_t photon = 0;      // merge: the grid slot
  Rgb value = Rgb::Zero();  // f(x) / p(x) (merge: VCM's estimate of this photon)
  double w = 0;             // VCM's MIS weight of the strategy for x
};

// Per-thread scratch (no allocation per sample once warmed up).
struct GvcmScratch {
  std::vector<pathspace::BidirVertex> camera;
  std::vector<pathspace::VcmPrefix> cp, off_cp, off_lp;
  Vec2 raster{0, 0};
  std::vector<GvcmTerm> terms;
  gradients::CameraSubpathShift shift;
  gradients::LightTracingShift lt;
  gradients::MergeShift merge;
  PairSplats splats;  // what the sample adds (flushed whole or dropped)
};

class GvcmTracer {
 public:
  GvcmTracer(const scene::Scene& scene, const GvcmSettings& settings, const VcmIteration& it,
             const LightPathStore& light, const PhotonGrid& grid);
  void sample(int px, int py, core::Rng& rng, GvcmScratch& scratch, gradients::GradientBuffers& buf,
              GvcmCounters& counters) const;

 private:
  void connections(int px, int py, const pathspace::BidirVertex* light, const pathspace::VcmPrefix* lp, int nl,
                   GvcmScratch& sc, int w, int h, GvcmCounters& counters) const;
  void merges(int px, int py, GvcmScratch& sc, GvcmCounters& counters) const;
  void offsets(int nb, const pathspace::BidirVertex* light, const pathspace::VcmPrefix* lp, GvcmScratch& sc, int w,
               int h, GvcmCounters& counters) const;
  const scene::Scene& m_scene;
  GvcmSettings m_settings;
  const VcmIteration& m_it;
  const LightPathStore& m_light;
  const PhotonGrid& m_grid;
  float m_merge_norm = 0;  // 1 / (pi r^2 N)
  gradients::BidirShiftOptions m_shift;
  bool m_pair_primal = true;
};

}  // namespace dp::integrators
