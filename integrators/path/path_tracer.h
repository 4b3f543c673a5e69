// Per-sample physics of the unidirectional path tracer: radiance along one camera ray.
// Camera-first paths; next-event estimation and BSDF sampling combined with the power
// heuristic (Veach 1997, Eq. 9.13, beta = 2); Russian roulette after rr_depth segments
// with survival probability min(0.95, max throughput component). max_depth counts path
// segments: a directly visible light is a path of depth 1.
#pragma once

#include <cmath>

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/path/path_settings.h"
#include "scene/scene.h"

namespace dp::integrators {

// Hot-loop counters, flushed into core::Stats once per tile (a string-keyed map
// lookup per ray would cost more than the ray).
struct PathCounters {
  int64_t rays = 0, shadow_rays = 0, rr_terminated = 0;
  void flush(core::Stats& stats) const {
    stats.add("pt.rays", rays);
    stats.add("pt.shadow_rays", shadow_rays);
    stats.add("pt.rr_terminated", rr_terminated);
  }
};

class PathTracer {
 public:
  PathTracer(const scene::Scene& scene, const PathSettings& settings, int max_depth)
      : m_scene(scene), m_settings(settings), m_max_depth(max_depth) {}
  // Radiance arriving at the camera along `ray` (may be non-finite; the caller drops it).
  Rgb radiance(const Ray& ray, core::Rng& rng, PathCounters& counters) const;

 private:
  Rgb next_event(const scene::SurfaceHit& hit, const Vec3& wi_local, const scene::BsdfContext& ctx,
                 core::Rng& rng, PathCounters& counters) const;
  const scene::Scene& m_scene;
  PathSettings m_settings;
  int m_max_depth;
};

// Power heuristic with beta = 2 for two strategies (Veach 1997, Eq. 9.13).
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a > 0.0f ? a / (a + b) : 0.0f;
}

// The same for three strategies: pdf_a^2 / (pdf_a^2 + pdf_b^2 + pdf_c^2), in double (the
// densities' ratios can be large); 1 for an infinite pdf_a.
inline float power_heuristic(float pdf_a, float pdf_b, float pdf_c) {
  if (std::isinf(pdf_a)) return 1.0f;
  const double a = double(pdf_a) * double(pdf_a), b = double(pdf_b) * double(pdf_b), c = double(pdf_c) * double(pdf_c);
  return a > 0.0 ? float(a / (a + b + c)) : 0.0f;
}

}  // namespace dp::integrators
