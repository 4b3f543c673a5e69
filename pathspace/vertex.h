// Path vertices. A vertex stores where it is (the full SurfaceHit: position, geometric
// normal, shading frame, uv, BSDF, emitter, shape/primitive ids), how the path arrived
// (wi, local shading frame) and, if the walk continued, how it left: the sampled lobe,
// f(wi, wo) |cos wo| and the solid-angle pdf of wo. Units and measures:
//  * pdf: solid-angle density of the outgoing direction as the walk samples it (BSDF
//    sampling, including the lobe-selection probability); for a Dirac lobe it is the
//    discrete probability of choosing that lobe and f_cos is weight * pdf (the lobe's
//    "value", e.g. Fresnel times reflectance).
//  * rr: Russian-roulette continuation probability applied after this vertex (1 if none).
//  * emission: radiance leaving this vertex toward the previous one (Le), 0 if none.
// The camera vertex is x_0 (kind camera, hit.p = eye); an escaped ray ends the path with
// an environment vertex (kind environment, wo_world = escape direction).
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace dp::pathspace {

enum class VertexKind : uint8_t { camera, surface, environment };

struct Vertex {
  VertexKind kind = VertexKind::surface;
  scene::SurfaceHit hit;       // surface vertices; camera: hit.p = eye
  Vec3 wi{0, 0, 1};            // local shading frame, toward the previous vertex
  Vec3 wo{0, 0, 1};            // local shading frame, toward the next vertex (if continued)
  Vec3 wo_world{0, 0, 1};      // world direction toward the next vertex
  Rgb emission = Rgb::Zero();  // Le toward the previous vertex
  Rgb f_cos = Rgb::Zero();     // scattering value toward the next vertex (see header)
  double pdf = 0;              // solid-angle pdf of wo (or discrete lobe probability)
  float rr = 1;                // continuation probability after this vertex
  float u_lobe = 0;            // lobe-selection sample (reused to pick the same Dirac lobe)
  float eta = 1;               // relative IOR eta_o / eta_i of the sampled lobe
  uint32_t lobe = 0;           // sampled LobeFlags bit, 0 = the walk did not continue
  bool connectable = false;    // classification (classify.h)

  bool is_surface() const { return kind == VertexKind::surface; }
  bool continued() const { return lobe != 0; }
  bool delta_lobe() const { return (lobe & scene::kDelta) != 0; }
  const Vec3& p() const { return hit.p; }
};

// Next-event-estimation record at a surface vertex: a point (or direction) on an
// emitter, sampled by Emitter::sample_direct. pdf = emitter pmf * solid-angle density
// at the vertex (delta lights: pmf). bsdf_pdf is the solid-angle pdf of BSDF sampling
// the same direction (0 for delta lights: BSDF sampling cannot hit them).
struct LightSample {
  bool valid = false;          // NEE was performed at this vertex
  const scene::Emitter* emitter = nullptr;
  Vec2 u{0, 0};                // the 2D sample given to sample_direct (delta lights reuse it)
  Vec3 p{0, 0, 0}, n{0, 0, 1};  // point on the emitter and its normal (area lights)
  Vec3 w{0, 0, 1};             // world direction vertex -> light
  Vec3 wo{0, 0, 1};            // the same in the vertex's local shading frame
  float dist = 0;              // distance (infinite for env / directional)
  bool delta = false;          // delta light (point, spot, directional)
  bool infinite = false;       // environment or directional
  bool visible = false;        // shadow ray unoccluded
  bool connectable = true;     // classification of the light point
  Rgb radiance = Rgb::Zero();  // arriving at the vertex before visibility
  Rgb f_cos = Rgb::Zero();     // BSDF value * |cos| toward the light
  double pdf = 0;              // light-sampling density (see header)
  double bsdf_pdf = 0;
};

}  // namespace dp::pathspace
