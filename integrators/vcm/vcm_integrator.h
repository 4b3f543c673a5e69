// `--integrator vcm`: vertex connection and merging (Georgiev et al. 2012) and its
// sub-algorithms (settings `mode`: vcm, bpt, vm, ppm, lt; vcm_settings.h), organised as
// SmallVCM: each iteration traces one light path per pixel (vcm_light_pass.h), builds a
// photon grid over their vertices if the mode merges (photon_grid.h), then traces one
// camera path per pixel (vcm_camera.h). The merging radius shrinks per iteration,
// r_i = r_0 i^((alpha-1)/2), r_0 = `radius` x the scene's bounding-sphere radius.
// `--spp` = iterations; `--time` runs whole iterations until the budget is used; an
// interrupted iteration is discarded, so the image is the average of complete ones.
#pragma once

#include "integrators/integrator.h"
#include "integrators/vcm/vcm_settings.h"

namespace dp::integrators {

class VcmIntegrator final : public Integrator {
 public:
  explicit VcmIntegrator(Settings& settings) : m_settings(VcmSettings::read(settings)) {}
  explicit VcmIntegrator(const VcmSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "vcm"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial / --mpi: parts split whole iterations; the raw sum "radiance", count "spp".
  bool supports_raw() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  VcmSettings m_settings;
};

}  // namespace dp::integrators
