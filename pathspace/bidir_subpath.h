// Camera and light subpaths for bidirectional path tracing (vertex convention in
// bidir_vertex.h). Both walks sample BSDFs (TransportMode radiance from the camera,
// importance from the lights), store forward and reverse area densities per vertex,
// and stop at a miss, a surface without material, a sidedness violation (geometric and
// shading normals disagree), Russian roulette (survival min(0.95, max beta) once the
// subpath has rr_depth segments; not part of the MIS densities) or max_vertices.
// Randomness comes only from `rng` (fixed order per sample: deterministic).
#pragma once

#include <vector>

#include "core/rng.h"
#include "pathspace/bidir_media.h"

namespace dp::pathspace {

struct SubpathParams {
  int max_vertices = 9;  // camera: max_depth + 1 (z_0 included); light: max_depth
  int rr_depth = 5;
  // Stop once a vertex has sampled a non-Dirac lobe (that vertex is kept, its successor
  // is not traced): G-PM needs the camera subpath only up to z_b.
  bool stop_after_smooth = false;
  // Grid media (bidir_media.h): counts the walks' delta-tracking free flights (optional).
  GridTracking* grid = nullptr;
};

// z_0 = pinhole, z_1 .. along the primary ray through `raster` (continuous pixels).
void camera_subpath(const scene::Scene& scene, const Vec2& raster, const SubpathParams& params, core::Rng& rng,
                    std::vector<BidirVertex>& out);
// y_0 on a light chosen by Scene::sample_emitter, y_1 .. (empty if the scene has no light).
void light_subpath(const scene::Scene& scene, const SubpathParams& params, core::Rng& rng,
                   std::vector<BidirVertex>& out);

// A ray leaving a light chosen by Scene::sample_emitter, drawn as light_subpath draws
// y_0 and its direction (same random numbers), and the throughput it carries,
// Le |cos| / (p(y_0) p(direction)) (lights at infinity: planar origin density). False
// when nothing is emitted. Light tracers that walk their own paths (photons through
// media, integrators/media_photons; volpath's light tracing) start here. `endpoint`, if
// given, receives y_0 (its emitter, position, normal and pdf_fwd = light_pdf_pos).
bool emit_light_ray(const scene::Scene& scene, core::Rng& rng, Ray& ray, Rgb& beta, BidirVertex* endpoint = nullptr);

// Continues `path` (a subpath in `mode`'s order: light-first for importance, camera-
// first for radiance) by exactly n vertices, without Russian roulette: an empty path
// starts at a new endpoint (the pinhole, then a raster uniform on the whole image; a
// light chosen by Scene::sample_emitter), a kept light point emits anew, a surface
// vertex samples its BSDF (its wi must be set; delta, lobe, u_lobe, pdf_out set here).
// False if the walk ends before n vertices (a miss, a surface without material, a
// sidedness violation, a light at infinity or the pinhole to continue from). The
// path-space mutations' walks (mcmc/mut_bidir.h); a radiance walk that escapes ends
// on an environment vertex, which the caller must accept or refuse.
bool extend_subpath(const scene::Scene& scene, std::vector<BidirVertex>& path, int n, scene::TransportMode mode,
                    core::Rng& rng);

// Rays between subpath vertices leave from the vertex itself (Scene::trace_from,
// scene/scene.h: not Scene::spawn_ray's origin pushed along the normal), so consecutive
// vertices lie on the sampled directions and the densities, cosines and shift Jacobians
// evaluated from positions agree with the sampled ones to float round-off.
// The first hit along w from surface vertex `from` (into `out`); false on a miss.
bool next_hit(const scene::Scene& scene, const scene::SurfaceHit& from, const Vec3& w, scene::SurfaceHit& out);
// A ray from point p (a light's surface point) along w, anchored at p.
Ray anchored_ray(const scene::Scene& scene, const Vec3& p, const Vec3& w);

// Re-derives wi, pdf_fwd and pdf_rev of every vertex of a given chain from the vertex
// positions, as the walk in `mode` from path[0] (the pinhole, or a light endpoint) would
// have set them; `delta` flags are kept (Dirac lobes give 0 densities). Tests use it to
// cut one full path into the subpaths of every strategy.
void recompute_densities(const scene::Scene& scene, std::vector<BidirVertex>& path, scene::TransportMode mode);
// Appends v (position, surface data, delta flag set) to `path` with wi and pdf_fwd derived
// from the positions, and the reverse density of its predecessor's predecessor, as the
// walk would have set them (recompute_densities for one vertex).
void append_vertex(const scene::Scene& scene, std::vector<BidirVertex>& path, const BidirVertex& v,
                   scene::TransportMode mode);

}  // namespace dp::pathspace
