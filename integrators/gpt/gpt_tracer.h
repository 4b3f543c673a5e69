// Per-sample physics of gradient-domain path tracing (Kettunen et al. 2015): one base
// walk (pathspace::PathBuilder, sampled exactly like the reference PT) in pixel i, its
// four shifted offsets (gradients::ReconnectionShift, or gradients::ManifoldShift with
// `shift=manifold`) into the neighbours, and the
// symmetric MIS-weighted splats (gradients/mis.h) of every concrete path into the
// primal, dx, dy and direct buffers:
//   primal_i += 1/4 w f(x)/p(x), primal_j += 1/4 w f(T x)|T'|/p(x) per neighbour pair
//   (each pair gives an unbiased estimate of both pixels; the primal averages the four),
//   gradient(i -> j) += w (f(T x)|T'| - f(x)) / p(x), stored as dx/dy of the forward pair.
// Directly visible emitters (depth 1) go to `direct` only and are never shifted
// (ALGORITHMS.md). A pair whose neighbour lies outside the image has no offset terms.
#pragma once

#include <array>
#include <memory>

#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "gradients/reconnection_shift.h"
#include "manifold/walk_stats.h"
#include "integrators/gpt/gpt_settings.h"
#include "pathspace/path_builder.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats once per tile.
struct GptCounters {
  int64_t samples = 0, nan_dropped = 0;
  int64_t media_skipped = 0;  // samples traced without any medium code (GptTracer: scenes without media)
  int64_t shifts = 0, shifts_full = 0, shifts_outside = 0;
  std::array<int64_t, gradients::kShiftStatusCount> fail{};      // walk failures by cause
  std::array<int64_t, gradients::kStepKindCount> attempted{}, succeeded{};  // per strategy
  std::array<int64_t, gradients::kShiftStatusCount> nee_fail{};
  int64_t nee_base_zero = 0;  // base light samples of zero density (not shift failures)
  manifold::WalkStats walks;  // manifold shift: walks by outcome ("gpt.manifold.*")
  int64_t walks_refused = 0;  // converged walks not used: the reverse shift would copy
  void flush(core::Stats& stats) const;
};

class GptTracer {
 public:
  GptTracer(const scene::Scene& scene, const GptSettings& settings, int max_depth);
  // One base sample in pixel (px, py) with its four offsets.
  void sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
              GptCounters& counters) const;
  const gradients::Shift& shift() const { return *m_shift; }
  const pathspace::PathBuilder& builder() const { return m_builder; }

 private:
  void count(const pathspace::Path& base, const gradients::ShiftResult& r, GptCounters& c) const;
  const scene::Scene& m_scene;
  GptSettings m_settings;
  pathspace::PathBuilder m_builder;
  std::unique_ptr<gradients::Shift> m_shift;
};

}  // namespace dp::integrators
