// Small helpers shared by the G-BDPT / G-VCM shifts of bidirectional paths
// (bidir_shift.cpp, light_rejoin.cpp, merge_shift.cpp). Internal to gradients/.
#pragma once

#include <cmath>

#include "pathspace/bidir_vertex.h"

namespace dp::gradients::bidir {

using pathspace::BidirKind;
using pathspace::BidirVertex;

inline double remap(float pdf) { return pdf != 0.0f ? double(pdf) : 1.0; }

// Connectable as a reconnection end: a light endpoint, or a surface with a smooth lobe.
inline bool smooth_surface(const BidirVertex& v) { return v.bsdf && !v.bsdf->is_purely_delta(); }

// f(wi, wo) |cos wo| at surface vertex v in `mode` (shading normal), 0 on a sidedness
// violation of either direction (as pathspace::connect).
inline Rgb scatter(const BidirVertex& v, const Vec3& wi_world, const Vec3& wo_world, scene::TransportMode mode) {
  if (!v.bsdf) return Rgb::Zero();
  const Vec3 wi = v.sp.shading.to_local(wi_world), wo = v.sp.shading.to_local(wo_world);
  if (!(v.sp.ng.dot(wi_world) * wi.z() > 0.0f) || !(v.sp.ng.dot(wo_world) * wo.z() > 0.0f)) return Rgb::Zero();
  return v.bsdf->eval(scene::BsdfContext{v.sp.uv, mode}, wi, wo) * std::abs(wo.z());
}

inline bool blocked(const scene::Scene& scene, const BidirVertex& from, const BidirVertex& to) {
  if (to.infinite()) return scene.occluded(scene.spawn_ray(from.sp, to.sp.ng));
  return scene.occluded(scene.spawn_segment(from.sp, to.sp.p));
}

inline BidirVertex surface_vertex(const scene::SurfaceHit& hit, const BidirVertex& like, const Vec3& toward_prev) {
  BidirVertex v = pathspace::surface_vertex_at(hit);
  v.wi = toward_prev;
  v.delta = like.delta;
  v.lobe = like.lobe;
  v.u_lobe = like.u_lobe;
  v.rr_out = like.rr_out;
  return v;
}

// Unit direction from `from` toward vertex `to` (the light's direction at infinity).
inline Vec3 direction(const BidirVertex& from, const BidirVertex& to) {
  return to.infinite() ? Vec3(to.sp.ng) : Vec3((to.sp.p - from.sp.p).normalized());
}

}  // namespace dp::gradients::bidir
