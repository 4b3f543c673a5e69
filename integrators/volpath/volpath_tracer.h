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
  // Light tracing (volpath_light.cpp).
  int64_t light_paths = 0;      // light paths traced
  int64_t light_chains = 0;     // ... reaching a vertex x after Dirac vertices only
  int64_t light_links = 0;      // connections of x to the camera or a camera-path vertex
  int64_t light_blocked = 0;    // ... occluded, outside the image, or with no value
  int64_t light_unmatched = 0;  // ... MNEE does not return the chain (left to BSDF sampling)
  int64_t light_added = 0;      // ... with a value (splatted, or added to the camera sample)
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
  // Light tracing (volpath_light.cpp): the end x of a light path that reached it through
  // Dirac vertices only (light -> s_m .. s_1 -> x), to be connected to the camera and to
  // every vertex of the camera path.
  struct LightEnd {
    bool ok = false;
    bool surface = false;
    scene::SurfaceHit hit;   // surface: x
    Vec3 p{0, 0, 0};         // x
    Vec3 d_in{0, 0, 1};      // the direction the light path arrived along
    int medium = -1;         // the medium it arrived in
    Rgb beta = Rgb::Zero();  // its throughput arriving at x (with x's free-flight weight)
    MneeConnection chain;    // s_1 .. s_m in MNEE's order (m, reflect_mask, verts)
    const scene::Emitter* emitter = nullptr;
    Vec3 y{0, 0, 0}, n_y{0, 0, 1};
  };
  // Radiance arriving at the camera along `ray` (may be non-finite; the caller drops it);
  // with `light`, its connections to the camera path's vertices are included.
  Rgb radiance(const Ray& ray, core::Rng& rng, VolpathCounters& counters, const LightEnd* light = nullptr) const;
  // Light tracing runs: settings.light_tracing, MNEE on, homogeneous media.
  bool light_tracing() const { return m_light_tracing; }
  // One light path (one per camera sample); false if it reached no x.
  bool trace_light(core::Rng& rng, VolpathCounters& counters, LightEnd& out) const;
  // Its connection to the camera: false if it adds nothing, else the pixel it lands in
  // (`raster`, continuous) and its MIS-weighted value, in units where the image is
  // sum(values) * pixel count / light paths (pathspace/bidir_connect.h, t = 1).
  bool splat_light(const LightEnd& light, core::Rng& rng, VolpathCounters& counters, Vec2& raster, Rgb& value) const;
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
  // `flight` (light tracing, homogeneous media): multiplied by free flight's probability
  // of passing each sub-segment, or with scatter_at_origin its density of a scatter at
  // r.o for the first one (a flight toward r.o ending there).
  MarchEnd march(Ray r, int& medium, const Vec3* target, core::Rng& rng, VolpathCounters& counters, Rgb& tr,
                 scene::SurfaceHit& stop, double* flight = nullptr, bool scatter_at_origin = false) const;
  // Light tracing (volpath_light.cpp). A vertex of the camera path that light tracing
  // connects to: the camera (depth 0), a medium or a non-Dirac surface vertex.
  struct CameraVertex {
    enum class Kind : uint8_t { none, camera, medium, surface } kind = Kind::none;
    MneeAnchor at;           // the vertex as MNEE's anchor: position, arrival, medium, depth
    Rgb beta = Rgb::Ones();  // the camera path's throughput arriving here
    const Vec3& p() const { return at.position(); }
    static CameraVertex of(const MneeAnchor& a, const Rgb& beta) {
      CameraVertex v;
      v.kind = a.surface ? Kind::surface : Kind::medium;
      v.at = a;
      v.beta = beta;
      return v;
    }
  };
  // The MIS weight of a BSDF/phase path that reached the light `hit` through the
  // refractions `chain` after the anchor x (volpath_mnee.h, "The BSDF side").
  struct ChainTrack {
    bool active = false;
    MneeAnchor anchor;
    int m = 0;
    uint32_t reflect_mask = 0;
    std::array<Vec3, kMaxMneeChain> verts{};
    CameraVertex prev;  // the camera vertex before x (light tracing)
    void start(const MneeAnchor& x, const CameraVertex& v) {  // a new anchor: no Dirac vertex after it yet
      active = true;
      anchor = x;
      prev = v;
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
  // `prev`: the camera vertex before x, for light tracing's weight (x.lt).
  Rgb mnee_nee(const MneeAnchor& x, const NeeProbe& probe, const CameraVertex& prev, core::Rng& rng,
               VolpathCounters& counters) const;
  float mnee_bsdf_weight(const ChainTrack& chain, const scene::SurfaceHit& hit, core::Rng& rng,
                         VolpathCounters& counters) const;
  // The solution of S(x, y) that is `path` (its m, reflect_mask and verts), if MNEE returns it.
  bool mnee_find(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, const MneeConnection& path, core::Rng& rng,
                 VolpathCounters& counters, MneeConnection& match) const;

  // Light tracing (volpath_light.cpp): the camera vertex.
  CameraVertex camera_vertex() const;
  // The link from camera vertex v to anchor x: the camera path's density of x drawn from v
  // (v's direction density / d^2, |cos| at a surface x, free flight's along the segment;
  // camera: pdf_direction), v's scattering value f_v toward x (BSDF |cos|, phase; camera:
  // pdf_direction) and the transmittance; false if the segment is blocked.
  bool link(const CameraVertex& v, const MneeAnchor& x, core::Rng& rng, VolpathCounters& counters, double& pdf,
            Rgb& f_v, Rgb& tr) const;
  // x with lt set where light tracing can make its paths: a camera vertex v precedes it.
  MneeAnchor linked(MneeAnchor x, const CameraVertex& v) const {
    x.lt = m_light_tracing && v.kind != CameraVertex::Kind::none;
    return x;
  }
  // The camera path's density of x drawn from v (link's), 0 if the segment is blocked.
  double camera_pdf(const CameraVertex& v, const MneeAnchor& x, core::Rng& rng, VolpathCounters& counters) const;
  // The light path's end joined to camera vertex v: the unweighted value times light
  // tracing's MIS weight (0 where MNEE does not return its chain).
  Rgb connect_light(const LightEnd& light, const CameraVertex& v, core::Rng& rng, VolpathCounters& counters) const;
  // Light tracing's density of the path x, s_1 .. s_m, y (light `e`, normal n_y; s_m the
  // vertex next to y) without the camera side's density of x: p_pos(y) p_dir(y -> s_m)
  // `factors` G / |cos_y|, with factors the Dirac lobes' and free flight's probabilities,
  // G the generalized geometry term.
  double light_trace_density(const MneeAnchor& x, const scene::Emitter& e, const Vec3& y, const Vec3& n_y,
                             const Vec3& s_m, double factors, double G) const;

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
  Rgb trace(const Ray& primary, core::Rng& rng, VolpathCounters& counters, const LightEnd* light) const;
  void set_light_tracing();  // m_light_tracing from the settings and the scene

  const scene::Scene& m_scene;
  VolpathSettings m_settings;
  int m_max_depth;
  bool m_has_media;
  int m_camera_medium;
  bool m_mnee;  // settings.mnee, nee, and a refractive surface in a scene with media
  bool m_equiangular;  // settings.equiangular and nee in a scene with media
  bool m_light_tracing;  // settings.light_tracing, m_mnee, homogeneous media only
  std::vector<int> m_shapes;  // specular shapes of MNEE's shape families (volpath_mnee.h)
};

}  // namespace dp::integrators
