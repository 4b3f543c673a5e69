// GD-MLT's direct light: paths of at most 2 segments (emitters seen directly and direct
// lighting of the first hit) by the reference path tracer, the part of the image the
// chains do not sample (Manzi et al. 2014, Sec. 4: "direct illumination ... separately").
// Rendered in passes that may be interleaved with the chains' rounds, so an interrupted
// render has both parts; each pass has its own random streams (seed, pass index).
#pragma once

#include <vector>

#include "integrators/gdmlt/gdmlt_settings.h"
#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"

namespace dp::integrators {

class DirectPass {
 public:
  DirectPass(const scene::Scene& scene, const GdmltSettings& settings, const RenderOptions& options);
  // Adds `spp` samples per pixel (fewer in tiles an interruption skipped).
  void render(int spp);
  core::Image image() const;
  int64_t spp_done() const { return m_spp; }
  int64_t nan_dropped() const { return m_dropped; }
  bool partial() const { return m_partial; }

 private:
  const scene::Scene& m_scene;
  PathTracer m_tracer;
  RenderOptions m_opt;
  int m_w, m_h;
  std::vector<Rgbd> m_sum;
  std::vector<int64_t> m_count;  // samples per pixel
  int64_t m_spp = 0, m_dropped = 0, m_passes = 0;
  bool m_partial = false;
};

}  // namespace dp::integrators
