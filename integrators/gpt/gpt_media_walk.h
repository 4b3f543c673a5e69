// The base walk of G-PT in homogeneous media (GptMediaTracer), sampled as volpath samples
// (integrators/volpath/volpath_tracer.h: free flight, HG phase sampling, BSDF sampling,
// index-matched boundaries that are not vertices, NEE with the transmittance of the
// shadow edge, Russian roulette) and recorded vertex by vertex for the shift:
//  * x_0 is the camera, x_k the k-th scattering vertex: a medium vertex, a surface, or
//    an escape (environment, direction only). Vertex k was reached by segment k.
//  * beta: f/p of the prefix x_0..x_k including the edge into x_k (volpath's throughput).
//  * ff_in: the free-flight density of that edge (gpt_media_edge.h: P(pass) of each
//    boundary-delimited stretch, then p(t) at a medium vertex or P(pass) at a surface).
//  * edge_w: the free-flight weight of that edge (Tr sigma_s / p or Tr / P(pass)).
//  * scattering toward x_{k+1}: weight (f / pdf, volpath's sample weight), f and the
//    solid-angle pdf (phase function or BSDF), the Russian-roulette probability rr.
//  * nee: the light sample drawn at x_k (when NEE ran there), with its scattering value
//    and the shadow edge (MediaEdge), kept even when the base's value is zero: the offset
//    of a blocked or back-facing light sample may carry light.
// Measures: every pdf is a solid-angle density of a direction times, where noted, the
// edge's free-flight density (Gruson et al. 2018, Sec. 3.1, Eqs. 2-4: medium vertices
// have no cosine, sigma_s rho_p as their vertex term).
#pragma once

#include <vector>

#include "integrators/gpt/gpt_media_edge.h"
#include "pathspace/sample_stream.h"

namespace dp::integrators {

struct MediaLightSample {
  bool valid = false;  // a light point with pdf > 0 and radiance (the base's NEE path exists)
  const scene::Emitter* emitter = nullptr;
  Vec2 u{0, 0};
  Vec3 p{0, 0, 0}, n{0, 0, 1}, w{0, 0, 1};
  float dist = 0;
  bool delta = false, infinite = false;
  Rgb radiance = Rgb::Zero();
  double pdf = 0;          // emitter pmf * solid-angle density at the vertex
  Rgb f = Rgb::Zero();     // BSDF |cos| or phase value toward the light (0: wrong side)
  double scatter_pdf = 0;  // BSDF / phase solid-angle density of w (0 for delta lights)
  MediaEdge edge;          // the shadow edge
};

struct MediaVertex {
  bool medium = false, escaped = false;
  int medium_index = -1;  // medium vertex: its medium; surface: the medium it was reached through
  scene::SurfaceHit hit;  // surfaces
  Vec3 p{0, 0, 0};
  Vec3 d_in{0, 0, 1};     // unit propagation direction of the edge into this vertex
  Rgb beta = Rgb::Ones();
  double ff_in = 1;
  Rgb edge_w = Rgb::Ones();
  Rgb emission = Rgb::Zero();  // Le toward x_{k-1} (area light or environment)
  bool connectable = false;
  bool continued = false, delta_lobe = false;
  Vec3 wo{0, 0, 1};
  Rgb weight = Rgb::Ones(), f = Rgb::Zero();
  double pdf = 0;
  float rr = 1;
  MediaLightSample nee;
};

struct MediaPath {
  Vec2 raster{0, 0};
  Ray primary;
  std::vector<MediaVertex> v;
};

struct GptMediaWalkCounters {
  int64_t medium_vertices = 0, surface_vertices = 0, null_crossings = 0, null_limit = 0, rr_terminated = 0;
};

struct MediaWalkOptions {
  int max_depth = 5, rr_depth = 5;
  bool nee = true;
  float shift_threshold = 0.05f;
};

// Scattering at a vertex with propagation direction d_in into it, toward unit wo:
// f (BSDF |cos| or phase value) and the solid-angle pdf of sampling wo. False where a
// surface's shading and geometric normals disagree on a side (then f = 0, pdf = 0).
bool media_scatter_eval(const scene::Scene& scene, const MediaVertex& v, const Vec3& d_in, const Vec3& wo, Rgb& f,
                        float& pdf);

// The medium a ray leaving vertex v along w starts in.
int media_medium_toward(const scene::Scene& scene, const MediaVertex& v, const Vec3& w);

// Where an edge from v starts.
inline EdgeStart media_edge_start(const MediaVertex& v) {
  EdgeStart s;
  s.surface = v.medium ? nullptr : &v.hit;
  s.p = v.p;
  return s;
}

// Evaluates the light sample `ls` (emitter, point / direction, pdf and radiance already
// set) from vertex v reached along d_in: scattering value, pdf and shadow edge.
void media_eval_light(const scene::Scene& scene, const MediaVertex& v, const Vec3& d_in, MediaLightSample& ls);

// Samples one base path in pixel (px, py) (the sub-pixel position from `stream`).
void build_media_path(const scene::Scene& scene, const MediaWalkOptions& opt, int px, int py,
                      pathspace::SampleStream& stream, MediaPath& path, GptMediaWalkCounters& c);

}  // namespace dp::integrators
