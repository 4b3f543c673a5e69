// `--integrator gvpm`: gradient-domain volumetric photon mapping (G-VPM; Gruson et al.
// 2018, Sec. 4; docs/gvpm_plan.md), on the primal `vpm`: per iteration `photons` light
// paths through the media with parent records (media_photons/photon_tracer.h), a photon
// BVH and the progressive 3D radius (as vpm), then one camera sample per pixel
// (gvpm_tracer.h): the primary ray's medium gathers shifted to the four neighbours
// (camera copy t' = t, mixed photon shift, reconnection to the photon's parent, Eq. 19's
// MIS), the rest of vpm's camera path in the unshifted `direct` layer. Output layers as
// `gpt`: "" (the reconstruction chosen by `reconstruction`, default L1), recon_l1,
// recon_l2, primal, dx, dy, direct; alpha 0.2 (Sec. 6.1). `--spp` = iterations, `--time`
// whole iterations (an interrupted one is dropped), `--partial`/`--mpi`: part k of n
// runs the global iterations k, k + n, ... Without media no photon is traced and the
// camera paths run vpm's media-free variant (gvpm.photon_passes_skipped,
// gvpm.media_skipped; every gradient is then the T_0 fallback of nothing: 0, all in
// `direct`). Counters `gvpm.*` (gvpm_tracer.h).
// `--integrator gbre` (G-BRE, Sec. 5.1) is this integrator with GvpmSettings::gather =
// beam: the primary ray's segments are Point-Beam 3D queries (every photon within r of the
// segment, its gather point uniform on its chord) shifted as above with R's camera factor
// |chord| / |chord'|; the later segments use `bre`'s kernel=3d gather; counters `gbre.*`.
// `--integrator gbeam` (G-Beam, Sec. 5.2) is it with GvpmSettings::gather = beams: the
// light paths' medium segments are short photon beams (as `beam`, with parent records,
// in a BeamBvh); a primary-ray segment draws one photon per beam piece within r
// (uniform on the piece's chord, Beam-Beam 3D) and a gather point uniform on its camera
// chord, shifted as gbre's (the photon reconnected to its beam's start vertex); the later
// segments use `beam`'s Beam-Beam 3D gather; counters `gbeam.*`.
// `--integrator gplane` (G-Plane, Sec. 5.3) is it with GvpmSettings::gather = planes: the
// light pass of `plane` (planes, and the beams not from scattering events; plane_pass.h);
// a primary-ray segment's plane hits are shifted by rotating each plane about its light
// segment (gvpm_plane.cpp, gradients/volume_plane_shift.h) while its beam part goes
// unshifted to `direct`; the later segments use `plane`'s gather; counters `gplane.*`
// (with plane's plane_tests, intersections, occluded and the pass's planes_stored, ...).
#pragma once

#include <memory>

#include "core/json.h"
#include "integrators/gvpm/gvpm_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class GvpmIntegrator final : public Integrator {
 public:
  explicit GvpmIntegrator(Settings& settings) : m_settings(GvpmSettings::read(settings)), m_json(settings.to_json()) {}
  // `gbre`: the settings read by GvpmSettings::read_gbre.
  static std::unique_ptr<Integrator> make_gbre(Settings& settings) {
    GvpmSettings g = GvpmSettings::read_gbre(settings);
    return std::make_unique<GvpmIntegrator>(g, settings.to_json());
  }
  // `gbeam`: the settings read by GvpmSettings::read_gbeam.
  static std::unique_ptr<Integrator> make_gbeam(Settings& settings) {
    GvpmSettings g = GvpmSettings::read_gbeam(settings);
    return std::make_unique<GvpmIntegrator>(g, settings.to_json());
  }
  // `gplane`: the settings read by GvpmSettings::read_gplane.
  static std::unique_ptr<Integrator> make_gplane(Settings& settings) {
    GvpmSettings g = GvpmSettings::read_gplane(settings);
    return std::make_unique<GvpmIntegrator>(g, settings.to_json());
  }
  explicit GvpmIntegrator(const GvpmSettings& settings, core::Json json = {}) : m_settings(settings), m_json(std::move(json)) {}
  std::string name() const override { return m_settings.name(); }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  GvpmSettings m_settings;
  core::Json m_json;
};

}  // namespace dp::integrators
