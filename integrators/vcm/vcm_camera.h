// Second half of a VCM iteration: one camera subpath per pixel, combined with the
// iteration's light paths (Georgiev et al. 2012, Alg. 1): the camera walk hitting
// lights (s = 0), connections to the pixel's own light path (vcm, bpt) and merges with
// every photon within the iteration's radius (vcm, vm, ppm), MIS-weighted by
// pathspace/vcm_mis.h (ppm: unweighted, merging at the first non-Dirac lobe only).
// A merge adds f(z) * beta_z * beta_y / (pi r^2 N) (N light paths; Eq. 10 of the
// paper): the photon's throughput beta_y already holds the cosine at its predecessor.
#pragma once

#include <vector>

#include "core/rng.h"
#include "integrators/vcm/photon_grid.h"
#include "integrators/vcm/vcm_light_pass.h"

namespace dp::integrators {

// f(z.wi, wo) at a camera vertex a photon arrives at along wo (radiance mode, no cosine:
// the photon's throughput carries it); 0 if either direction violates sidedness.
Rgb merge_bsdf(const pathspace::BidirVertex& z, const Vec3& wo);

// The merging kernel at camera[t-1] (t >= 2): the iteration's radius and normalisation
// 1 / (pi r^2 N), with r^2 scaled by the adaptive kernel's prod c(z_1 .. z_(t-2)) =
// cp[t-2].m (pathspace/vcm_mis.h; 1 without it). radius 0 = no merge: below a factor of
// 1e-20 in r^2 (a few diffuse bounces) the kernel is skipped so that its normalisation
// cannot overflow; the MIS weight of such a merge is below ~1e-20 of its path's weights.
struct MergeKernel {
  float radius = 0, norm = 0;
  double shrink = 1;  // the r^2 factor
};
MergeKernel merge_kernel(float radius, float norm, const pathspace::VcmPrefix* cp, int t);

struct VcmCameraCounters {
  int64_t camera_vertices = 0, connections = 0, occluded = 0, merge_queries = 0, merges = 0, nan_dropped = 0;
  VcmCameraCounters& operator+=(const VcmCameraCounters& o) {
    camera_vertices += o.camera_vertices;
    connections += o.connections;
    occluded += o.occluded;
    merge_queries += o.merge_queries;
    merges += o.merges;
    nan_dropped += o.nan_dropped;
    return *this;
  }
};

struct VcmCameraScratch {
  std::vector<pathspace::BidirVertex> camera;
  std::vector<pathspace::VcmPrefix> prefixes;
};

class VcmCameraTracer {
 public:
  VcmCameraTracer(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it,
                  const LightPathStore& light, const PhotonGrid& grid);
  // Radiance estimate of one camera path through `raster` of pixel `pixel` (the index of
  // its light path); false (L untouched) if it was not finite.
  bool sample(const Vec2& raster, int64_t pixel, core::Rng& rng, VcmCameraScratch& scratch, Rgb& L,
              VcmCameraCounters& counters) const;

 private:
  Rgb merge(const pathspace::BidirVertex* camera, const pathspace::VcmPrefix* cp, int t,
            VcmCameraCounters& counters) const;
  const scene::Scene& m_scene;
  const VcmSettings& m_settings;
  const VcmIteration& m_it;
  const LightPathStore& m_light;
  const PhotonGrid& m_grid;
  float m_merge_norm = 0;  // 1 / (pi r^2 N)
};

}  // namespace dp::integrators
