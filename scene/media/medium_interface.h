// Which medium a ray is in after it leaves a surface (SCENE_FORMAT.md, `interior` and
// `exterior`). Medium indices are into Scene::media(); -1 is vacuum.
//  * A shape that declares neither `interior` nor `exterior` is not a medium boundary:
//    a ray crossing or leaving it keeps the medium it was in (so a scene-filling fog
//    fills a glass sphere that says nothing, as in pbrt and Mitsuba).
//  * A shape that declares either is a boundary: the side its geometric normal points
//    away from is `interior` (vacuum if not declared), the other side `exterior`
//    (the camera's medium if not declared, the format's default).
// Index-matched boundaries are shapes with `material: none` (the null BSDF, lobes ==
// kNull): integrators pass straight through them and only switch media.
#pragma once

#include "scene/bsdf/bsdf.h"
#include "scene/surface.h"

namespace dp::scene {

// The medium on the side of `hit` that unit world direction `w` points into.
inline int medium_toward(const SurfaceHit& hit, const Vec3& w, int current, int camera_medium) {
  if (hit.interior_medium < 0 && hit.exterior_medium < 0) return current;
  if (hit.ng.dot(w) < 0.0f) return hit.interior_medium;
  return hit.exterior_medium >= 0 ? hit.exterior_medium : camera_medium;
}

// True for an index-matched boundary: a surface that light passes unchanged.
inline bool is_index_matched(const SurfaceHit& hit) { return hit.bsdf && hit.bsdf->lobes() == kNull; }

}  // namespace dp::scene
