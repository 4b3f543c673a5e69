// The offset of one G-VCM strategy of a base path under one neighbour shift (Sun et al.
// 2017, Sec. 4-5; dispatch of gvcm_tracer.h): its value f(Tx)|T'|/p(x), VCM's MIS weight of
// the same strategy for the offset path, w(Tx), and the MIS ratio R = p_s(Tx)|T'| / p_s(x).
// Used by GvcmTracer and, on its own, by the MIS partition-of-unity test (test_gvcm_mis.cpp).
#pragma once

#include <vector>

#include "gradients/merge_shift.h"
#include "integrators/gvcm/gvcm_tracer.h"
#include "pathspace/vcm_mis.h"

namespace dp::integrators {

// One strategy of the base path.
struct GvcmStrategy {
  bool merge = false;
  int s = 0, t = 0;    // connection (s, t) (t = 1: light tracing through `raster`); merge at camera[t - 1]
  Vec2 raster{0, 0};   // t = 1: the base's projection
  // Connection: the light subpath and its prefixes. Merge: the photon's light subpath,
  // the photon light[j], its MIS record and throughput.
  const pathspace::BidirVertex* light = nullptr;
  const pathspace::VcmPrefix* lp = nullptr;
  int j = 0;
  pathspace::VcmPhotonMis photon;
  Rgb photon_beta = Rgb::Zero();
};

struct GvcmOffsetContext {
  const scene::Scene& scene;
  const pathspace::VcmMisConfig& mis;
  float merge_norm;  // 1 / (pi r^2 N) at the iteration's radius (before the adaptive kernel)
  const gradients::BidirShiftOptions& shift_options;
  const std::vector<pathspace::BidirVertex>& camera;  // the base camera subpath
  const std::vector<pathspace::VcmPrefix>& cp;        // its VCM prefixes
  const gradients::CameraSubpathShift& shift;         // its shift into the neighbour (strategies t >= 2, merges)
  const std::vector<pathspace::VcmPrefix>& off_cp;    // VCM prefixes of shift.path
};

struct GvcmOffset {
  Rgb value = Rgb::Zero();
  double w = 0;  // w(Tx)
  double R = 0;
};

// false: no offset (the T_0 fallback); `lt`, `merge`, `off_lp` are scratch.
bool gvcm_offset(const GvcmOffsetContext& ctx, const GvcmStrategy& st, const Vec2& offset,
                 gradients::LightTracingShift& lt, gradients::MergeShift& merge,
                 std::vector<pathspace::VcmPrefix>& off_lp, GvcmOffset& out, GvcmCounters& counters);

// The pinhole's VCM prefix on light tracing's camera side (as VCM's light pass).
extern const pathspace::VcmPrefix kGvcmPinholePrefix;

}  // namespace dp::integrators
