// Per-camera-sample physics of gradient-domain photon mapping (G-PM as Sun et al. 2017,
// Sec. 7, implement it: merging only at the first connectable camera vertex z_b, every
// other strategy's density 0). One camera subpath through a jittered position of pixel i,
// traced up to z_b (pathspace::SubpathParams::stop_after_smooth); every photon y_j of the
// iteration within r of z_b is merged (VCM's merge, Georgiev 2012 Eq. 10):
//   base = f(z_b; wi, photon wi) beta_L(y_j) beta_E(z_b) / (pi r^2 N).
// For each neighbour j the camera subpath is shifted once (gradients/bidir_shift.h: raster
// offset, Dirac copies up to z_b^off) and every merge is shifted by the merging shift
// (gradients/merge_shift.h: the photon's light subpath rejoined at z_b^off, Eq. 18-20):
//   off = f(x_off) / p_off(x*)  (its value over the same pi r^2 N).
// Gradient weight (Eq. 21-23 with one active and one passive strategy): w = 1 / (1 + R^beta),
// R = p(T x)|T'| / p(x) = [light side's area density toward z_b^off / toward the photon]
// x (r' / r)^2 (the offset pixel's own kernel at z_b^off; the camera prefixes' ratio is 1
// in raster coordinates). A failed shift is the T_0 fallback: -base.
// Radius: r = radius_factor x the pixel footprint at z_b (footprint_radius).
// Emission seen through a Dirac-only prefix (z_1 .. z_b) and merges at mixed vertices
// before z_b where the walk took the Dirac lobe are added to the `direct` layer, unshifted
// (no other strategy of G-PM samples them; counted).
#pragma once

#include <array>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "integrators/pair_splats.h"
#include "gradients/merge_shift.h"
#include "integrators/gpm/gpm_settings.h"
#include "integrators/kernel_footprint.h"
#include "integrators/vcm/photon_grid.h"
#include "integrators/vcm/vcm_light_pass.h"

namespace dp::integrators {

// Hot-loop counters in plain integers, flushed into core::Stats once per tile.
struct GpmCounters {
  int64_t samples = 0, nan_dropped = 0, no_merge_vertex = 0, direct = 0, unshifted_merges = 0;
  int64_t merge_queries = 0, wide_queries = 0, merges = 0, depth_skipped = 0;
  int64_t camera_shifts = 0, merge_shifts = 0, merge_shifted = 0, merge_chain = 0;
  std::array<int64_t, gradients::kShiftStatusCount> camera_fail{}, merge_fail{};
  int64_t pairs_shifted = 0, pairs_fallback = 0, outside_image = 0;
  manifold::WalkStats walks;  // the photons' chain walks (merging shift, specular predecessor)
  void flush(core::Stats& stats) const;
};

// One base merge at z_b.
struct GpmTerm {
  uint32_t photon = 0;      // grid slot
  Rgb value = Rgb::Zero();  // the base estimate (header)
};

// Per-thread scratch (no allocation per sample once warmed up).
struct GpmScratch {
  std::vector<pathspace::BidirVertex> camera;
  std::vector<GpmTerm> terms;
  gradients::CameraSubpathShift shift;
  gradients::MergeShift merge;
  PairSplats splats;  // what the sample adds (flushed whole or dropped)
};

class GpmTracer {
 public:
  // radius_factor: r = radius_factor x footprint (radius_scale x this iteration's shrink).
  GpmTracer(const scene::Scene& scene, const GpmSettings& settings, int max_depth, double radius_factor,
            const LightPathStore& light, const PhotonGrid& grid);
  void sample(int px, int py, core::Rng& rng, GpmScratch& scratch, gradients::GradientBuffers& buf,
              GpmCounters& counters) const;

 private:
  // The base merges at camera vertex k (radius r) into sc.terms; their sum.
  Rgb gather(const pathspace::BidirVertex& z, int k, double r, GpmScratch& sc, GpmCounters& counters) const;
  void offsets(int nb, int px, int py, const Vec2& raster, int b, double r, GpmScratch& sc, int w, int h,
               GpmCounters& counters) const;
  const scene::Scene& m_scene;
  GpmSettings m_settings;
  int m_max_depth;
  double m_radius_factor;
  double m_inv_paths;  // 1 / N
  const LightPathStore& m_light;
  const PhotonGrid& m_grid;
  gradients::BidirShiftOptions m_shift;
  bool m_pair_primal = true;
};

}  // namespace dp::integrators
