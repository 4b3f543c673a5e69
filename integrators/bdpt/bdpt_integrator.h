// `--integrator bdpt`: bidirectional path tracing (Veach 1997, Ch. 10; all s/t
// strategies, power or balance heuristic) scheduled over tiles with progressive passes.
// Image = camera-side estimate per pixel (divided by its sample count) + light-tracing
// splats (scaled by pixel count / light paths traced), merged deterministically
// (splat_merger.h). Every light kind: area, point, spot, directional, environment.
// Participating media: medium vertices, free flights and transmittances in the walks and
// connections (pathspace/bidir_media.h); grid media by delta tracking (walks) and ratio
// tracking (connections), with deterministic stand-ins for their MIS densities.
#pragma once

#include "integrators/bdpt/bdpt_settings.h"
#include "integrators/integrator.h"

namespace dp::integrators {

class BdptIntegrator final : public Integrator {
 public:
  explicit BdptIntegrator(Settings& settings) : m_settings(BdptSettings::read(settings)) {}
  // Tests: explicit settings (including BdptSettings::mis.fault).
  explicit BdptIntegrator(const BdptSettings& settings) : m_settings(settings) {}
  std::string name() const override { return "bdpt"; }
  RenderResult render(const scene::Scene& scene, const RenderOptions& options) override;
  // --partial / --mpi: the raw sums "camera" and "light" (splats) and the count "spp".
  bool supports_raw() const override { return true; }
  bool renders_media() const override { return true; }
  bool renders_grid_media() const override { return true; }
  RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const override;

 private:
  BdptSettings m_settings;
};

}  // namespace dp::integrators
