// Per-tile physics of gradient-domain path reusing (Bauszat et al. 2017, Sec. 3.2-3.3):
//  * the reuse tile T x T of the jittered tiling is extended by a one-pixel border to the
//    right and bottom (clipped to the image; Sec. 3.2, Fig. 4), so both pixels of every
//    forward pair whose first pixel is inside the tile belong to the extended tile;
//  * every pixel of the extended tile traces one base walk (correlated primary rays), and
//    every base walk x_k is reused in every pixel m of the extended tile by `pr`'s reuse
//    function and tile-constant balance weights (PrTracer::reuse, Eq. 3 and 7): the walk
//    is stored once and shifted to each pixel, giving F_k->m = w_k f_m(R x)|R'| / p_k(x);
//  * Eq. 8: the gradient of the pair (i, j) is sum_k (F_k->j - F_k->i) -- the difference of
//    the tile's two Eq. 7 estimates, so every base path is reused for every gradient of
//    the tile, and both members of a difference are shifts of one path (correlated);
//  * stitching (Fig. 4): only the inner part is written -- primal of the inner pixels, dx
//    and dy of the pairs whose first pixel is inner (including the pairs reaching into
//    the border) and the sample count of the inner pixels. The inner parts of one
//    iteration's tiles partition the image, so each pixel and each pair gets one estimate
//    per iteration;
//  * proportional Russian roulette on base paths (Sec. 3.3): base x_k survives with
//    q = max(min(1, lum(x_k) / delta), q_min), lum the luminance of its path-traced value
//    (NEE/BSDF power heuristic, as PT; direct emission excluded); a survivor's whole fan
//    F_k->m (its own pixel included: its weight needs the shifts) is weighted 1/q, so
//    E[fan] is unchanged. q_min > 0 matters: a base of value 0 can have shifted paths
//    that carry light;
//  * early out (early_out.h): a base's dark suffix behind a reconnection vertex is cut
//    before shifting; a base that cannot contribute anywhere is not shifted at all.
// Directly visible emitters (depth 1) go to the `direct` layer from each inner pixel's own
// base walk, never shifted (as gpt). A base whose fan has a non-finite value is dropped
// whole and counted once.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "gradients/pair_terms.h"
#include "integrators/gpr/gpr_settings.h"
#include "integrators/pr/pr_tracer.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats ("gpr.*") once per tile.
struct GprCounters {
  PrCounters reuse;  // shifts by strategy and failure cause, NaN drops ("gpr.shift.*", ...)
  int64_t bases = 0, rr_tested = 0, rr_skipped = 0;
  int64_t cut = 0, cut_vertices = 0, dark = 0;  // early out: walks cut, vertices cut, walks not shifted
  // The paper's Table 1: base paths with a nonzero value in an inner pixel's estimate, or
  // in one of the two pixels of an inner pair, summed over the estimates.
  int64_t pixel_estimates = 0, pixel_paths = 0, gradient_estimates = 0, gradient_paths = 0;
  void flush(core::Stats& stats) const;
};

class GprTracer {
 public:
  GprTracer(const scene::Scene& scene, const GprSettings& settings, int max_depth);
  // The extended tile of `inner` in a width x height image (border: see GprFaults).
  static ReuseTile extended(const ReuseTile& inner, int width, int height, bool border = true);
  // One iteration of the extended tile of `inner`: adds the inner part's primal, dx, dy,
  // direct and sample counts to `buf` (see the header comment).
  void render_tile(const ReuseTile& inner, core::Rng& rng, gradients::GradientBuffers& buf, GprCounters& c) const;
  // Survival probability of a base walk under the proportional Russian roulette.
  double survival(const pathspace::Path& base, gradients::PairTerms& scratch) const;
  const PrTracer& reuse() const { return m_pr; }

 private:
  const scene::Scene& m_scene;
  GprSettings m_settings;
  PrTracer m_pr;
};

}  // namespace dp::integrators
