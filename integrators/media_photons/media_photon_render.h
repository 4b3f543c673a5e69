// Iteration driver of the volumetric photon density estimators (`vpm`, `bre`). Iteration
// i (0-based, global): trace `photons` light paths through the media (photon_tracer.h),
// build the photon BVH, set the kernel radius r_i (volume_kernel.h, `kernel_dim`-
// dimensional), then render one camera path per pixel over 16x16 tiles in parallel
// (media_camera.h) with the integrator's MediumGather. The image is the average of the
// complete iterations (an interrupted one is dropped whole). `--spp` = iterations;
// `--time` runs whole iterations until the budget is used. Raw buffers as `path`'s
// ("radiance" sums, "spp" = iterations per pixel), so `--partial`/`--mpi`/`merge` work:
// part k of n runs the global iterations k, k + n, ... with their own radii and streams.
// On a scene without media no photon is traced and the camera paths run without medium
// code (counters <prefix>.media_skipped, <prefix>.photon_paths = 0). The driver itself
// is render_media_passes; render_media_photons gives it the photon-point pass.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/media_photons/media_camera.h"
#include "integrators/media_photons/media_photon_settings.h"
#include "integrators/media_photons/photon_bvh.h"
#include "integrators/media_photons/photon_tracer.h"

namespace dp::integrators {

// The gather of one iteration: its photons (BVH), kernel radius and emitted path count N.
using MakeGather =
    std::function<std::unique_ptr<MediumGather>(const PhotonBvh& photons, float radius, int64_t light_paths)>;

RenderResult render_media_photons(const scene::Scene& scene, const RenderOptions& options, const std::string& prefix,
                                  const MediaPhotonSettings& settings, int kernel_dim, const MakeGather& make_gather);

// The light pass of one iteration of a density estimator in media, for
// render_media_passes: `prepare` traces tp's light paths, builds what the gather needs
// and sets `gather` for kernel radius `radius` (false: interrupted by options.stop);
// `stats` are the pass's own counters (added to the result for complete iterations
// only); `release` frees the pass's data after the iteration's camera paths.
struct MediaLightPass {
  std::function<bool(const PhotonTraceParams& tp, float radius, PhotonTraceCounters& pc, core::Stats& stats,
                     std::unique_ptr<MediumGather>& gather)>
      prepare;
  std::function<void()> release;
  GatherCounterNames names;  // how the camera's gather counters are named
};

// The iteration driver behind render_media_photons (`vpm`, `bre`) with any light pass
// (`beam`'s photon beams): the same iterations, radii, streams, tiles and counters.
RenderResult render_media_passes(const scene::Scene& scene, const RenderOptions& options, const std::string& prefix,
                                 const MediaPhotonSettings& settings, int kernel_dim, const MediaLightPass& pass);

// First iteration's radius: radius_scale x the scene's bounding-box diagonal.
double initial_media_radius(const scene::Scene& scene, const MediaPhotonSettings& settings);

// The photon pass of global iteration `global` (vpm, bre, gvpm): `photons` light paths,
// the render's depth and seed, the settings' roulette depth, on `threads` threads.
PhotonTraceParams photon_pass_params(const MediaPhotonSettings& settings, const RenderOptions& options, int64_t global,
                                     int threads);

}  // namespace dp::integrators
