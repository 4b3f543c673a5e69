// Following a ray through MNEE's chain of Dirac vertices (internal to volpath_mnee*.cpp):
// the seed of a manifold walk and the scan of seeds (volpath_mnee_scan.cpp) both refract
// (or reflect) a direction from the anchor through m purely specular surfaces.
#pragma once

#include <optional>

#include "integrators/volpath/volpath_mnee.h"
#include "pathspace/scatter.h"
#include "scene/bsdf/bsdf.h"
#include "scene/scene.h"

namespace dp::integrators {

inline bool mnee_reflects(const scene::SurfaceHit& h) {
  return h.bsdf && h.bsdf->is_purely_delta() && (h.bsdf->lobes() & scene::kDeltaReflection) != 0;
}

// The Dirac lobe `lobe` at h for light arriving from -w_in (radiance mode, as volpath
// samples it); nullopt if the surface cannot scatter this way (TIR).
inline std::optional<scene::BsdfSample> mnee_dirac(const scene::SurfaceHit& h, const Vec3& w_in, uint32_t lobe) {
  const Vec3 wi = h.shading.to_local(-w_in);
  if (!pathspace::consistent_side(h, -w_in, wi.z())) return std::nullopt;
  auto bs = pathspace::sample_dirac_lobe(*h.bsdf, pathspace::radiance_context(h), wi, lobe, 0.5f);
  if (!bs || !(bs->pdf > 0.0f) || is_black(bs->weight)) return std::nullopt;
  return bs;
}

// A ray leaving the anchor along w.
inline Ray mnee_leave(const scene::Scene& scene, const MneeAnchor& x, const Vec3& w) {
  if (x.surface) return scene.continue_ray(x.hit, w);
  Ray r;
  r.o = x.p;
  r.d = w;
  r.tmin = 0.0f;
  r.tmax = kInfinity;
  return r;
}

// Traces from x along d through m Dirac vertices (bit i of `mask`: vertex i + 1 reflects,
// else refracts), all on `shape` unless it is -1. At each, on_vertex(hit, w_in, sample)
// may refuse it (false). Returns false where the chain breaks; else `r` leaves the last
// vertex along the scattered direction. Where the lobe cannot scatter (TIR) the chain breaks.
template <typename F>
bool follow_dirac_chain(const scene::Scene& scene, const MneeAnchor& x, const Vec3& d, int m, uint32_t mask,
                        int shape, Ray& r, const F& on_vertex) {
  r = mnee_leave(scene, x, d);
  Vec3 w = d;
  scene::SurfaceHit h;
  for (int i = 0; i < m; ++i) {
    const bool reflect = ((mask >> i) & 1u) != 0;
    if (!scene.intersect(r, h) || (shape >= 0 && h.shape != shape) || !(reflect ? mnee_reflects(h) : mnee_refracts(h)))
      return false;
    const auto bs = mnee_dirac(h, w, reflect ? scene::kDeltaReflection : scene::kDeltaTransmission);
    if (!bs || !on_vertex(h, w, *bs)) return false;
    w = h.shading.to_world(bs->wo);
    r = scene.continue_ray(h, w);
  }
  return true;
}

}  // namespace dp::integrators
