// One edge of a G-PT path in homogeneous media (Gruson et al. 2018, Sec. 3.1, Eq. 2): the
// segment between two scattering vertices (or toward a light, or to infinity) traced
// through index-matched boundaries (`material: none`, scene/media/medium_interface.h),
// with what the shift needs of it:
//  * tr: the Beer-Lambert transmittance tau of every medium crossed (Eq. 2);
//  * ff: the free-flight density of a walk sampling this edge: the product over the
//    sub-segments between boundaries (each restarts the free flight, as volpath does) of
//    P(pass), the last one ending in p(len) at a medium vertex or P(pass) at a surface or
//    at infinity (scene/media/free_flight.h);
//  * sigma_s of the end's medium when the edge ends at a medium vertex.
// Any other surface blocks the edge. Only homogeneous media (gpt refuses grid media).
#pragma once

#include "scene/scene.h"

namespace dp::integrators {

struct MediaEdge {
  bool blocked = false;  // a surface other than an index-matched boundary, or too many boundaries
  Rgb tr = Rgb::Ones();
  double ff = 1;
  int end_medium = -1;   // the medium of the last sub-segment
  int crossings = 0;
};

// Where an edge starts: a surface vertex (the ray leaves it by Scene::trace_from, the one
// rule of every walk) or a point in a medium / the camera (a plain ray from p).
struct EdgeStart {
  const scene::SurfaceHit* surface = nullptr;
  Vec3 p{0, 0, 0};
};

// Traces from `start` along unit `d` for `len` (kInfinity: to infinity) in `medium` (the
// medium the ray starts in, -1 vacuum). `to_medium_vertex`: the edge ends at a medium
// vertex (p(len)) rather than a surface or infinity (P(pass)); at a surface end the last
// stretch of the scene epsilon is not searched for hits (the target itself).
MediaEdge trace_media_edge(const scene::Scene& scene, const EdgeStart& start, const Vec3& d, float len, int medium,
                           bool to_medium_vertex);

// The offset's primary ray: traced from the camera through index-matched boundaries to
// its first other surface (t < 0) or to distance t from the origin (a medium vertex,
// Gruson 2018, Sec. 4.1: t' = t). Fails (blocked) if a surface comes first at distance t,
// or nothing is hit for a surface end. `hit` gets the surface of a surface end.
MediaEdge trace_primary(const scene::Scene& scene, const Ray& ray, float t, scene::SurfaceHit& hit);

}  // namespace dp::integrators
