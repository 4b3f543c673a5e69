// The direct light of the MCMC integrators: paths of at most 2 segments (emitters seen
// directly and direct lighting of the first hit) by the reference path tracer, the part
// of the image the chains do not sample (GD-MLT: Manzi et al. 2014, Sec. 4, "direct
// illumination ... separately"; path-space MLT: Mitsuba 0.6's directSamples).
// Rendered in passes that may be interleaved with the chains' rounds, so an interrupted
// render has both parts; each pass has its own random streams (seed, pass index).
// Parts (RenderOptions::part/parts, issue 17): each pass is a tile render split into the
// parts' (pass, tile) work units (tile_scheduler.h); parts that make the same sequence
// of render() calls hold disjoint samples whose raw sums and counts ("direct") add up to
// the single render's.
#pragma once

#include <string>
#include <vector>

#include "core/raw_image.h"
#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"

namespace dp::integrators {

class DirectPass {
 public:
  // `label`: the progress line's name ("gdmlt direct", ...).
  DirectPass(const scene::Scene& scene, const PathSettings& settings, const RenderOptions& options, std::string label);
  // Adds `spp` samples per pixel (fewer in tiles an interruption skipped).
  void render(int spp);
  // Renders 1-spp passes until `spp` samples per pixel (the passes an interleaved single
  // render made after rounds this part did not need: the same calls, the same streams).
  void catch_up(int64_t spp);
  core::Image image() const;
  // Sum "direct" and count "direct" into `raw`; the image of such buffers.
  void write(core::RawImage& raw) const;
  static core::Image image(const core::RawImage& raw);
  int64_t spp_done() const { return m_spp; }
  int64_t nan_dropped() const { return m_dropped; }
  bool partial() const { return m_partial; }

 private:
  const scene::Scene& m_scene;
  PathTracer m_tracer;
  RenderOptions m_opt;
  std::string m_label;
  int m_w, m_h;
  std::vector<Rgbd> m_sum;
  std::vector<int64_t> m_count;  // samples per pixel
  int64_t m_spp = 0, m_dropped = 0, m_passes = 0;
  bool m_partial = false;
};

}  // namespace dp::integrators
