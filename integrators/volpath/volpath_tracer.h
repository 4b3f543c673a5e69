// Per-sample physics of the volumetric path tracer: radiance along one camera ray
// through homogeneous participating media (Gruson et al. 2018, Sec. 3.1, Eqs. 2-4: the
// path throughput is the product of vertex terms rho (BSDF, or sigma_s times the phase
// function), edge transmittances tau and geometry terms, whose cosines are 1 at medium
// vertices).
//  * Each segment that starts in a medium samples a free-flight distance
//    (scene/media/free_flight.h, one-sample MIS over RGB channels): a scatter before the next
//    surface makes a medium vertex, otherwise the weight Tr / P(pass) carries the
//    segment's transmittance to the surface.
//  * Next-event estimation at surface and medium vertices: the shadow ray passes
//    index-matched boundaries (`material: none`), multiplying the closed-form
//    transmittance of each medium it crosses; any other surface blocks it. Combined with
//    BSDF or phase sampling by the power heuristic (Veach 1997, Eq. 9.13, beta = 2); the
//    light density of a hit reached through index-matched boundaries is taken from the
//    last scattering vertex, where NEE sampled it.
//  * Index-matched boundaries are not vertices: crossing one changes the medium
//    (scene/media/medium_interface.h) and costs no depth; refractive boundaries (dielectrics)
//    are ordinary surface vertices whose sampled direction picks the medium.
//  * Russian roulette after rr_depth segments as `path`. max_depth counts scattering
//    segments (surface and medium vertices), a directly visible light is depth 1.
// Without media in the scene (Scene::caps().has_media false) the tracer runs a variant
// compiled without any medium code; it equals `path`'s algorithm (the null BSDF is then
// a Dirac lobe, as in `path`), and the counter volpath.media_skipped counts its paths.
#pragma once

#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/volpath/volpath_settings.h"
#include "scene/scene.h"

namespace dp::integrators {

// Hot-loop counters, flushed into core::Stats once per tile.
struct VolpathCounters {
  int64_t rays = 0, shadow_rays = 0, rr_terminated = 0;
  int64_t medium_scatter = 0;          // medium vertices (free flight ended before the surface)
  int64_t medium_pass = 0;             // segments through a medium that reached the surface or escaped
  int64_t surface_events = 0;          // surface vertices (BSDF sampled)
  int64_t null_crossings = 0;          // index-matched boundaries passed by path rays
  int64_t shadow_null_crossings = 0;   // ... by shadow rays
  int64_t null_limit = 0;              // paths or shadow rays cut after kMaxNullCrossings boundaries
  int64_t media_skipped = 0;           // paths traced without any medium code (scene without media)
  int64_t grid_flights = 0;            // free flights by delta tracking (grid media)
  void flush(core::Stats& stats) const;
};

class VolpathTracer {
 public:
  VolpathTracer(const scene::Scene& scene, const VolpathSettings& settings, int max_depth);
  // Radiance arriving at the camera along `ray` (may be non-finite; the caller drops it).
  Rgb radiance(const Ray& ray, core::Rng& rng, VolpathCounters& counters) const;
  // A guard against rays caught between index-matched boundaries (numerical trouble):
  // more crossings than this end the path (or block the shadow ray), counted.
  static constexpr int kMaxNullCrossings = 256;

  // Also used by the photon density estimators' camera paths (integrators/media_photons),
  // whose surface vertices are volpath's:
  // NEE at a surface vertex in medium `medium` (the medium on the light's side is found
  // from the sampled direction).
  template <bool kMedia>
  Rgb next_event_surface(const scene::SurfaceHit& hit, const Vec3& wi_local, const scene::BsdfContext& ctx,
                         int medium, core::Rng& rng, VolpathCounters& counters) const;
  // NEE at a medium vertex p of medium `medium`, reached along direction d.
  Rgb next_event_medium(const Vec3& p, const Vec3& d, int medium, core::Rng& rng, VolpathCounters& counters) const;
  // Transmittance of the shadow ray `r` that starts in `medium` (through index-matched
  // boundaries up to r.tmax); 0 if a surface blocks it. `target`: the light point, or
  // nullptr for a light at infinity.
  Rgb shadow_transmittance(Ray r, int medium, const Vec3* target, core::Rng& rng, VolpathCounters& counters) const;

 private:
  template <bool kMedia>
  Rgb trace(const Ray& primary, core::Rng& rng, VolpathCounters& counters) const;

  const scene::Scene& m_scene;
  VolpathSettings m_settings;
  int m_max_depth;
  bool m_has_media;
  int m_camera_medium;
};

}  // namespace dp::integrators
