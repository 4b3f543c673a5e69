// `--integrator beam`: progressive photon beams (Jarosz et al. 2011, "Progressive photon
// beams" and "A comprehensive theory of volumetric radiance estimation using photon points
// and beams"; the primal Beam of Gruson et al. 2018, Sec. 5.2 and 6.1). Per iteration
// `photons` light paths are traced as for `vpm` (media_photons/photon_tracer.h) and every
// segment they travel inside a scattering medium is kept as a short photon beam (no photon
// points); the beams go into a BVH over pieces of at most max(16 r, diag / 128)
// (beam_bvh.h). Camera paths are `vpm`'s (volpath on surfaces,
// media_photons/media_camera.h); each camera segment inside a medium queries the beams
// within r and adds the Beam-Beam 3D (`kernel: 3d`, default) or Beam x Beam 1D
// (`kernel: 1d`) estimate (beam_gather.h). The radius shrinks per iteration with the
// kernel's dimension D (3 or 1), r_{i+1}^D = r_i^D (i + alpha) / (i + 1)
// (media_photons/volume_kernel.h). `--spp` = iterations, `--time` whole iterations,
// `--partial`/`--mpi` as `vpm` (media_photons/media_photon_render.h).
// Counters `beam.*`: beams_stored, beams_clipped, beam_nan_dropped, beam_pieces (light
// pass), medium_segments, queries, beam_candidates (beam pieces within r of a segment,
// same medium, depth allowed), contributions (candidates with a non-zero estimate),
// beams_depth_skipped, empty_segments, parallel_skipped (1D), plus the photon pass's and
// the camera paths' (photon_paths, rays, ...; photons_stored is 0: no point is kept).
// Without media no light path is traced (photon_passes_skipped, media_skipped). Info:
// media, kernel, kernel_dimension, radius_initial, radius_final, photons_per_iteration.
#pragma once

#include "integrators/beam/beam_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class BeamIntegrator final : public Integrator {
 public:
  explicit BeamIntegrator(Settings& settings) : m_settings(BeamSettings::read(settings)) {}
  explicit BeamIntegrator(const BeamSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "beam"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }  // beams by delta tracking (beam_gather.h)
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  BeamSettings m_settings;
};

}  // namespace dp::integrators
