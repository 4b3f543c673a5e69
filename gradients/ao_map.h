// Screen-space ambient-occlusion map guiding the incremental manifold walk (Manzi et al.
// 2014, Sec. 4 "Ambient Occlusion for Incremental Manifold Walk", Sec. 5 parameters).
// Lives in gradients/ because kernels_adaptive/ had no committed build file yet; the
// shift itself never includes it (it receives an OcclusionDecision, incremental_shift.h).
//
// Build: one primary ray per pixel through the pixel centre; at its hit, `rays`
// cosine-distributed secondary rays (shading-frame hemisphere facing the camera). The
// pixel's coefficient is the fraction of secondary rays hitting something closer than
// the threshold length = radius * max(width, height) pixels, each pixel's footprint taken
// at the primary hit's distance ("0.75% of the image size ... projected", radius 0.0075):
// the world threshold grows with depth. Misses count as long. Pixels whose primary ray
// misses have no coefficient. Deterministic for any thread count: pixel p draws from
// core::Rng(seed, p).
// Lookup at a world point: project to the raster (camera.h), depth test against the
// pixel's primary hit (|distance - depth| <= depth_tolerance * depth + one footprint);
// a point not visible to the camera has no coefficient (-1: never declared).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace dp::gradients {

struct AoMapSettings {
  float radius = 0.0075f;          // fraction of the image size (Manzi 2014, Sec. 5)
  int rays = 16;                   // secondary rays per pixel
  float depth_tolerance = 0.01f;   // relative depth test
  uint64_t seed = 1;
  int threads = 0;                 // 0: all hardware threads
};

class AoMap {
 public:
  AoMap(const scene::Scene& scene, const AoMapSettings& settings);
  // Coefficient in [0, 1] at pixel (x, y), -1 where the primary ray missed.
  float at_pixel(int x, int y) const { return m_ao[size_t(y) * size_t(m_w) + size_t(x)]; }
  float depth(int x, int y) const { return m_depth[size_t(y) * size_t(m_w) + size_t(x)]; }
  // Coefficient at world point p if the camera sees it (depth test), else -1.
  float lookup(const Vec3& p) const;
  int width() const { return m_w; }
  int height() const { return m_h; }

 private:
  const scene::Scene& m_scene;
  AoMapSettings m_opt;
  int m_w = 0, m_h = 0;
  std::vector<float> m_ao, m_depth, m_footprint;  // footprint: world size of a pixel per unit distance
};

}  // namespace dp::gradients
