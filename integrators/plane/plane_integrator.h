// `--integrator plane`: progressive photon planes (Bitterli & Jarosz 2017; the primal
// Plane of Gruson et al. 2018, Sec. 5.3, Plane-Beam 0D). Per iteration `photons` light
// paths are traced as for `vpm`/`beam` (media_photons/photon_tracer.h, same streams);
// every medium scattering event keeps a photon plane (its segment x the sampled
// direction, media_photons/photon_plane.h) and every medium segment that does not start at
// a scattering event a short photon beam. Planes go into a BVH over pieces (plane_bvh.h),
// beams into `beam`'s (beam/beam_bvh.h). Camera paths are `vpm`'s
// (media_photons/media_camera.h); each camera segment in a medium adds the planes' 0D
// estimate (one shadow ray per intersection) and the beams' Beam-Beam 3D estimate
// (plane_gather.h derives both and why nothing is counted twice). Only the beams' radius
// shrinks, r_{i+1}^3 = r_i^3 (i + alpha) / (i + 1). `--spp` = iterations, `--time`
// whole iterations, `--partial`/`--mpi` as `vpm` (media_photons/media_photon_render.h).
// Counters `plane.*`: planes_stored, planes_clipped, plane_dropped, plane_pieces,
// beams_stored (those kept for the beam part), beams_to_planes (beams from scattering
// events, left to the planes), beam_pieces (light pass); medium_segments, queries (beam
// queries), beam_candidates, plane_tests (pieces whose box a segment passes),
// intersections (= plane_shadow_rays), occluded, plane_parallel, contributions,
// depth_skipped, empty_segments, plus the photon pass's and camera paths' counters.
// Grid media: planes from every medium segment with ratio-tracked transmittances along
// both directions and the camera segment, sigma_s at the plane points (plane_gather.h,
// "Grid media"; counter plane.grid_planes); the beams are `beam`'s grid beams.
// Without media no light path is traced (photon_passes_skipped, media_skipped) and every
// plane.* work counter is 0. Info: media, kernel_dimension (3, the beams'), radius_initial/final.
#pragma once

#include "integrators/integrator.h"
#include "integrators/plane/plane_settings.h"

namespace dp::integrators {

class PlaneIntegrator final : public Integrator {
 public:
  explicit PlaneIntegrator(Settings& settings) : m_settings(PlaneSettings::read(settings)) {}
  explicit PlaneIntegrator(const PlaneSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "plane"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }  // planes from ratio tracking (plane_gather.h)
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  PlaneSettings m_settings;
};

}  // namespace dp::integrators
