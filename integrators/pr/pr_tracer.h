// Per-tile physics of generalized path reusing (Bauszat et al. 2017, Sec. 3.1, Eq. 7):
//  * one base walk per pixel of the tile (pathspace::PathBuilder, sampled exactly like the
//    reference PT), all with the same sub-pixel position (correlated primary rays, Sec. 3.2:
//    the pixel filters of a base path and its reused paths agree);
//  * every base walk x_q reused in every other pixel p of the tile by the reuse function
//    R_qp = the G-PT shift by the integer offset p - q (gradients::ReconnectionShift:
//    pixel p's own primary vertex, then half-vector copies through glossy/specular
//    vertices until it reconnects to x_q, Sec. 3.1). With the same sub-pixel position the
//    primary ray of the shifted path is pixel p's own, so R_p(x_p, x_q) of Eq. 7 and its
//    Jacobian |R'| = |T'| of the shift;
//  * each concrete path (NEE or BSDF, >= 2 segments, gradients::PairTerms) weighted by the
//    balance heuristic over the tile's samplers (gradients::tile_balance_weight, Eq. 3),
//    constant over the tile, and splatted as w f_p(R x)|R'| / p_q(x) into pixel p (and as
//    w f_q(x) / p_q(x) into q). A failed reuse contributes 0 to that pixel and its
//    sampler drops out of the weights' denominators. A light sample occluded from the
//    base's or the offset's vertex counts as a failed reuse of that NEE path, as a
//    blocked reconnection fails a BSDF path, so both techniques see the same samplers.
// Directly visible emitters (1 segment) go to each pixel from its own base walk only.
// Exactness of the tile-constant weight needs R_pm(R_qp x) = R_qm x (the paper's Sec. 3.1
// bijectivity argument): the reconnection shift has it when every shift of a walk takes the
// same strategy at every vertex, so R is the shift with match_classes (an offset vertex of
// another class than its base vertex -- connectable or glossy/specular -- fails the reuse;
// without it, a tile straddling a glossy and a diffuse surface gave weights summing to 0..2).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/pair_terms.h"
#include "gradients/reconnection_shift.h"
#include "gradients/shift.h"
#include "integrators/pr/pr_settings.h"
#include "integrators/pr/reuse_tiling.h"
#include "pathspace/path_builder.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats once per tile.
struct PrCounters {
  int64_t tiles = 0, base_paths = 0, bases_without_paths = 0;
  int64_t shifts = 0, shifts_full = 0;
  std::array<int64_t, gradients::kShiftStatusCount> fail{}, nee_fail{};  // by cause
  std::array<int64_t, gradients::kStepKindCount> attempted{}, succeeded{};  // per strategy
  int64_t nee_base_zero = 0;  // base light samples of zero density (not shift failures)
  int64_t class_mismatch = 0;  // of fail[not_invertible]: an offset vertex of another class
  int64_t own = 0, reused = 0;  // (base, pixel) estimates with a nonzero value: own pixel, other pixels
  int64_t nan_dropped = 0;
  // Into counters "<prefix>.*" (`gpr` reuses the tracer under its own name).
  void flush(core::Stats& stats, const std::string& prefix = "pr") const;
};

// One base walk reused over its tile: the per-pixel estimates and the tile's MIS weight
// of each of its concrete paths (indexed by key(): segments and strategy).
struct ReuseFan {
  std::vector<Rgbd> value;       // per tile pixel: sum over concrete paths of w f(R x)|R'| / p(x)
  std::vector<double> weight;    // per key: w_q,self (Eq. 3), 0 where the base has no such path
  std::vector<double> other;     // per key: p_q,other / p_q,self of the base
  std::vector<uint8_t> present;  // per key: the base has this concrete path
  // Sum of the weights of pixel q's two techniques for the path of `key`:
  // w_q,self + w_q,other = weight (1 + other).
  double own_weight_sum(size_t key) const { return weight[key] * (1.0 + other[key]); }
  static size_t key(int segments, bool nee) { return size_t(2 * segments + (nee ? 1 : 0)); }

  // Scratch (reused between base walks).
  gradients::PairTerms pairs;
  gradients::ShiftResult res;
  std::vector<double> denom;
  std::vector<Rgbd> fb;
  struct Splat {
    int pixel;
    size_t key;
    Rgbd fo;
  };
  std::vector<Splat> splats;
};

class PrTracer {
 public:
  PrTracer(const scene::Scene& scene, const PrSettings& settings, int max_depth);
  // One iteration of one reuse tile: adds every pixel's estimate (Eq. 7, plus its directly
  // visible emission) to sum[y * width + x]. Non-finite estimates are counted and dropped.
  void render_tile(const ReuseTile& tile, core::Rng& rng, int width, std::vector<Rgbd>& sum,
                   PrCounters& counters) const;
  // The tile's base walks (row-major), one shared sub-pixel position.
  void build_bases(const ReuseTile& tile, core::Rng& rng, std::vector<pathspace::Path>& bases) const;
  // Reuses `base` (sampled in tile pixel q, row-major index) in every pixel of the tile.
  // `tile_bases` (the tile's base walks, build_bases): each offset takes its pixel's
  // primary ray and hit from there instead of re-tracing them (Bauszat 2017, Sec. 3.3);
  // null: traced (the same offsets up to float rounding of the raster position).
  void reuse(const pathspace::Path& base, int q, const ReuseTile& tile, ReuseFan& fan, PrCounters& counters,
             const std::vector<pathspace::Path>* tile_bases = nullptr) const;
  const gradients::Shift& shift() const { return *m_shift; }
  const pathspace::PathBuilder& builder() const { return m_builder; }

 private:
  void count(const pathspace::Path& base, const gradients::ShiftResult& r, PrCounters& c) const;
  const scene::Scene& m_scene;
  PrSettings m_settings;
  pathspace::PathBuilder m_builder;
  std::unique_ptr<gradients::Shift> m_shift;
  const gradients::ReconnectionShift* m_reconnect = nullptr;  // m_shift as a reconnection shift, if it is one
};

}  // namespace dp::integrators
