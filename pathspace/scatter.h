// Local scattering helpers shared by the path builder and the shift mappings.
#pragma once

#include <optional>

#include "pathspace/vertex.h"

namespace dp::pathspace {

// A direction is usable at a surface only if the geometric and shading normals agree on
// its side (as in the reference path tracer: no light leaks through shading normals).
inline bool consistent_side(const scene::SurfaceHit& hit, const Vec3& w_world, float cos_local) {
  return hit.ng.dot(w_world) * cos_local > 0.0f;
}

// Paths continue from a surface vertex with Scene::continue_ray / Scene::trace_from (the
// origin at the vertex, the one rule of every integrator and shift: scene/scene.h).

inline scene::BsdfContext radiance_context(const scene::SurfaceHit& hit) {
  return scene::BsdfContext{hit.uv, scene::TransportMode::radiance};
}

// Samples the Dirac lobe `lobe` of `bsdf` for incoming wi: tries the given lobe-selection
// sample first, then the extremes of [0, 1) (lobe selection is by thresholds on u_lobe).
// Returns nullopt if the BSDF cannot produce that lobe for this wi.
std::optional<scene::BsdfSample> sample_dirac_lobe(const scene::Bsdf& bsdf, const scene::BsdfContext& ctx,
                                                   const Vec3& wi, uint32_t lobe, float u_lobe);

// NEE density (emitter pmf * solid angle at `from`) of choosing the emitter point of the
// surface vertex `light` (area emitters) or the escape direction (environment vertex).
double light_pdf(const scene::Scene& scene, const Vec3& from, const Vertex& light);

// Emitted radiance of vertex v toward direction w_world (pointing away from v):
// area emission for surfaces, environment radiance along -w for environment vertices.
Rgb emitted(const scene::Scene& scene, const Vertex& v, const Vec3& w_world);

}  // namespace dp::pathspace
