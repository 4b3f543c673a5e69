// Camera paths of the volumetric photon density estimators (`vpm`, `bre`): surface
// vertices exactly as volpath's (BSDF sampling, NEE with the shadow ray's transmittance,
// power-heuristic MIS, index-matched boundaries, Russian roulette; volpath_tracer.h), but
// the camera path never scatters in a medium. Each segment it travels inside a medium
// instead asks a MediumGather for the light scattered toward the camera along it,
//   L_m = int_0^s Tr(c, x_t) sigma_s L_i(x_t, -w) dt        (Gruson et al. 2018, Eq. 5:
// the photon estimate replaces the last camera edge dc and the light edge ab), and the
// path goes on to the surface with the segment's transmittance Tr(s) as a factor
// (no free-flight sampling; closed form, or ratio tracking in a grid medium). Every light path is so counted once: its
// vertices up to the first medium vertex seen from the camera by the camera path, the
// rest by a photon (photon_tracer.h). max_depth: a gather on the t-th camera segment uses
// photons of depth <= max_depth - t (volpath's path length).
// Without media (Scene::caps().has_media false) a variant compiled without medium code
// runs, equal to volpath's (counter <prefix>.media_skipped).
#pragma once

#include <string>

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/volpath/volpath_tracer.h"
#include "scene/scene.h"

namespace dp::integrators {

struct GatherCounters {
  int64_t segments = 0;     // camera segments inside a medium (one gather each)
  int64_t queries = 0;      // photon-map queries (points for vpm, beams for bre)
  int64_t photons = 0;      // photons that contributed (inside a kernel, depth allowed)
  int64_t depth_skipped = 0;   // photons inside a kernel left out by the path-length limit
  int64_t empty_segments = 0;  // segments skipped: nothing scatters along them (sigma_t = 0 or infinite)
  int64_t candidates = 0;      // beam-beam candidates (`beam`: beams within r of the segment, depth allowed)
  int64_t parallel = 0;        // `beam` (1D kernel): candidates parallel to the segment, no closest point
  int64_t plane_tests = 0;     // `plane`: plane pieces whose box the segment passes (intersection solved)
  int64_t intersections = 0;   // `plane`: segment-plane intersections inside both (depth, medium allowed)
  int64_t occluded = 0;        // `plane`: intersections whose shadow ray a1(t0) -> b was blocked
};

// Sidecar names of the gather counters (<prefix>.<name>): the photon estimators' by
// default; `beam` names its own (beam_integrator.h). A null name is not written.
struct GatherCounterNames {
  const char* queries = "queries";
  const char* gathered = "photons_gathered";
  const char* depth_skipped = "photons_depth_skipped";
  const char* candidates = nullptr;
  const char* parallel = nullptr;
  bool planes = false;  // `plane`: also plane_tests, intersections (= shadow rays), occluded
};

// The in-scattered radiance along one camera segment inside medium `medium`: the ray
// (unit d) from its origin to t = seg_len (may be +inf), photons of depth <=
// max_photon_depth. Thread-safe (const, randomness from `rng`).
class MediumGather {
 public:
  virtual ~MediumGather() = default;
  virtual Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                     GatherCounters& counters) const = 0;
};

struct MediaCameraCounters {
  VolpathCounters surface;  // rays, shadow rays, surface vertices, crossings (volpath's fields)
  GatherCounters gather;
  void flush(core::Stats& stats, const std::string& prefix, const GatherCounterNames& names = {}) const;
};

class MediaCameraTracer {
 public:
  MediaCameraTracer(const scene::Scene& scene, int rr_depth, int max_depth);
  // Radiance along the camera ray (may be non-finite: the caller drops it). `gather` may
  // be null only on a scene without media.
  Rgb radiance(const Ray& ray, const MediumGather* gather, core::Rng& rng, MediaCameraCounters& counters) const;

 private:
  template <bool kMedia>
  Rgb trace(const Ray& primary, const MediumGather* gather, core::Rng& rng, MediaCameraCounters& counters) const;

  const scene::Scene& m_scene;
  VolpathTracer m_volpath;  // its surface NEE and shadow transmittance
  int m_rr_depth, m_max_depth;
  bool m_has_media;
};

}  // namespace dp::integrators
