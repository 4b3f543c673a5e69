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
#include "integrators/volpath/volpath_mnee.h"
#include "integrators/volpath/volpath_settings.h"
#include "manifold/walk_stats.h"
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
  // Manifold NEE (volpath_mnee.h).
  int64_t mnee_attempts = 0;     // light samples whose straight segment a refractive surface blocks
  int64_t mnee_shape_attempts = 0;  // shape families tried (mnee_shapes; per specular shape)
  int64_t mnee_chains = 0;       // ... blocked by refractive surfaces only (a chain to solve)
  int64_t mnee_seed_failed = 0;  // the refracted seed missed a boundary or the light's plane
  int64_t mnee_walk_failed = 0;  // the manifold walk did not reach y
  int64_t mnee_occluded = 0;     // the solved chain is blocked, or its lobes do not follow it
  int64_t mnee_connections = 0;  // contributions added
  int64_t mnee_scan_rays = 0;      // seed chains traced by the scans (mnee_scan)
  int64_t mnee_scan_brackets = 0;  // ... sign changes of the miss: one seed each
  int64_t mnee_scan_folds = 0;     // ... minima of |miss| whose parabola crosses zero: two seeds
  int64_t mnee_scan_edges = 0;     // ... ends of a valid run where |miss| still shrinks: one seed
  int64_t mnee_scan_fallbacks = 0; // scans without a seed: one walk from the straight (or centre) direction
  int64_t mnee_bsdf_hits = 0;    // BSDF/phase paths reaching a light through refractions only
  int64_t mnee_bsdf_matched = 0; // ... that MNEE also returns (weighted by MIS, else 1)
  // Equiangular NEE (volpath_equiangular.cpp).
  int64_t equiangular_samples = 0;   // segments with an equiangular light connection
  int64_t equiangular_skipped = 0;   // ... none: a light at infinity drawn, or y on the ray's line
  int64_t equiangular_occluded = 0;  // the connection was blocked
  manifold::WalkStats mnee_walks;  // MNEE's manifold walks (volpath.mnee.walk.*)
  manifold::WalkStats mnee_seeds;  // its seeds' exact re-traces (volpath.mnee.seed.*)
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
  // `probe` (volpath's own tracer) receives the light point and whether MNEE may apply.
  Rgb next_event_surface(const scene::SurfaceHit& hit, const Vec3& wi_local, const scene::BsdfContext& ctx,
                         int medium, core::Rng& rng, VolpathCounters& counters, NeeProbe* probe = nullptr) const;
  // The free-flight segment a medium vertex was drawn on (with `equiangular`): the MIS of
  // NEE and phase sampling there counts equiangular sampling.
  struct FlightSegment {
    bool active = false;
    Vec3 o{0, 0, 0}, d{0, 0, 1};
    float t_max = 0, t = 0;
    float pdf = 0;  // free-flight density of t
  };
  // NEE at a medium vertex p of medium `medium`, reached along direction d (on `flight`).
  Rgb next_event_medium(const Vec3& p, const Vec3& d, int medium, core::Rng& rng, VolpathCounters& counters,
                        NeeProbe* probe = nullptr, const FlightSegment* flight = nullptr) const;
  // Transmittance of the shadow ray `r` that starts in `medium` (through index-matched
  // boundaries up to r.tmax); 0 if a surface blocks it. `target`: the light point, or
  // nullptr for a light at infinity.
  Rgb shadow_transmittance(Ray r, int medium, const Vec3* target, core::Rng& rng, VolpathCounters& counters) const;

  // The MNEE solutions S(x, y) from anchor x to the light point y (normal n_y), at most
  // `max_chain` refractions (volpath_mnee.h; volpath_mnee.cpp).
  // refraction_hint false: the straight segment is known not to be blocked by a
  // refractive surface first (reflection chains only).
  MneeSolutions mnee_connect(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int max_chain, bool refraction_hint,
                             core::Rng& rng, VolpathCounters& counters) const;

 private:
  // Where a marched ray ended: r.tmax or no surface (reached), the first surface that is not
  // an index-matched boundary (surface; `stop`), or the crossing limit.
  enum class MarchEnd : uint8_t { reached, surface, limit };
  // Transmittance of `r` (starting in `medium`, updated at each index-matched crossing).
  MarchEnd march(Ray r, int& medium, const Vec3* target, core::Rng& rng, VolpathCounters& counters, Rgb& tr,
                 scene::SurfaceHit& stop) const;
  // The MIS weight of a BSDF/phase path that reached the light `hit` through the
  // refractions `chain` after the anchor x (volpath_mnee.h, "The BSDF side").
  struct ChainTrack {
    bool active = false;
    MneeAnchor anchor;
    int m = 0;
    uint32_t reflect_mask = 0;
    std::array<Vec3, kMaxMneeChain> verts{};
    void start(const MneeAnchor& x) {  // a new anchor: no Dirac vertex after it yet
      active = true;
      anchor = x;
      m = 0;
      reflect_mask = 0;
    }
  };
  // One seed direction d's solution of a chain of m Dirac vertices (bit i of `mask`: vertex
  // i + 1 reflects, else refracts), all on `shape` unless it is -1; none if it repeats one
  // of `found`.
  MneeConnection mnee_solve(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, uint32_t mask, int shape,
                            const Vec3& d, const MneeSolutions& found, core::Rng& rng,
                            VolpathCounters& counters) const;
  // Calls f(direction) for MNEE's seed directions across the bounds b (mnee_seeds - 1).
  template <typename F>
  void for_seeds(const Vec3& xp, const Vec3& y, const Bounds3& b, const F& f) const;
  // Calls f(direction) for each seed of one chain family across the bounds b: mnee_scan's
  // (or `first` if it has none), or with mnee_scan 0 `first` and for_seeds'.
  template <typename F>
  void seed_family(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, int shape, const Bounds3& b,
                   const Vec3& first, const F& f, VolpathCounters& counters) const;
  // Seeds from a scan of the chain's miss across the bounds b (mnee_scan directions;
  // volpath_mnee_scan.cpp): their count.
  int mnee_scan(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, int shape,
                const Bounds3& b, MneeSeeds& seeds, VolpathCounters& counters) const;
  // MNEE's NEE side: beta-less contribution F(X) / p_L * w_L of the probe's light point.
  Rgb mnee_nee(const MneeAnchor& x, const NeeProbe& probe, core::Rng& rng, VolpathCounters& counters) const;
  float mnee_bsdf_weight(const ChainTrack& chain, const scene::SurfaceHit& hit, core::Rng& rng,
                         VolpathCounters& counters) const;

  // Equiangular NEE on the segment ray.o + t ray.d, t in [0, t_max], of a medium:
  // beta-less, MIS-weighted (volpath_equiangular.cpp).
  Rgb next_event_equiangular(const Ray& ray, float t_max, int medium, core::Rng& rng, VolpathCounters& counters) const;
  // Equiangular sampling's density for the vertex of `flight` and the light point y (normal
  // n) of `emitter` chosen with probability pmf, over free flight's density of that vertex
  // (p_e / p_ff): in solid angle at the vertex for area lights (p_e q(y) r^2 / cos / p_ff),
  // dimensionless for Dirac lights (p_e / p_ff). 0 if equiangular sampling cannot make it.
  float equiangular_ratio(const FlightSegment& flight, const scene::Emitter& emitter, float pmf, const Vec3& y,
                          const Vec3& n) const;
  // Free flight's density of a scatter at t on the segment o + t d of `medium` (grid media:
  // the deterministic stand-in of volpath_equiangular.cpp).
  float flight_pdf(int medium, const Vec3& o, const Vec3& d, float t) const;

  template <bool kMedia>
  Rgb trace(const Ray& primary, core::Rng& rng, VolpathCounters& counters) const;

  const scene::Scene& m_scene;
  VolpathSettings m_settings;
  int m_max_depth;
  bool m_has_media;
  int m_camera_medium;
  bool m_mnee;  // settings.mnee, nee, and a refractive surface in a scene with media
  bool m_equiangular;  // settings.equiangular and nee in a scene with media
  std::vector<int> m_shapes;  // specular shapes of MNEE's shape families (volpath_mnee.h)
};

}  // namespace dp::integrators
