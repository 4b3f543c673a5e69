// Random walk with next-event estimation from the camera, driven only by a SampleStream.
// It samples exactly like the reference path tracer (integrators/path): BSDF sampling,
// NEE at every vertex that has a non-delta lobe, Russian roulette after rr_depth
// segments with q = min(0.95, max(beta)), max_depth path segments, consistent_side()
// checks of shading vs geometric normals. Coordinate layout of the stream (fixed, so a
// PrimarySampleStream coordinate always drives the same decision): 2 for the raster
// position inside the pixel, then 7 per surface vertex that may scatter: light choice,
// 2 for the light point, lobe choice, 2 for the BSDF warp, Russian roulette (drawn even
// when unused).
#pragma once

#include "pathspace/classify.h"
#include "pathspace/path.h"
#include "pathspace/sample_stream.h"

namespace dp::pathspace {

struct WalkOptions {
  int max_depth = 8;     // path segments (a directly seen light is depth 1)
  int rr_depth = 5;      // Russian roulette after this many segments
  bool nee = true;       // next-event estimation
  float shift_threshold = kDefaultShiftThreshold;  // vertex classification (classify.h)
};

class PathBuilder {
 public:
  PathBuilder(const scene::Scene& scene, const WalkOptions& options) : m_scene(scene), m_opt(options) {}
  // Builds the walk for pixel (px, py) into `path` (cleared first; its capacity is reused).
  void build(int px, int py, SampleStream& stream, Path& path) const;
  // Same, from an explicit raster position (no stream coordinates for it).
  void build_from_raster(const Vec2& raster, SampleStream& stream, Path& path) const;
  const WalkOptions& options() const { return m_opt; }
  const scene::Scene& scene() const { return m_scene; }

 private:
  void sample_light(Vertex& v, LightSample& ls, float u_light, const Vec2& u) const;
  const scene::Scene& m_scene;
  WalkOptions m_opt;
};

}  // namespace dp::pathspace
