// Vertex classification for shift mappings (Kettunen et al. 2015, Sec. 5; ALGORITHMS.md).
// A surface vertex is CONNECTABLE ("diffuse") when the lowest roughness of its BSDF's
// non-delta components is at least the threshold and, for Phong lobes, the exponent is
// at most kPhongExponentThreshold; otherwise it is glossy/specular and shifts copy its
// half vector. Defaults are the renderer-side defaults of SCENE_FORMAT.md ("roughness
// < 0.05 or phong exponent > 100 is not connectable"). BSDFs with only Dirac lobes report roughness 0 and are never
// connectable. A vertex without a BSDF (a pure emitter), an environment vertex and
// non-area light points are connectable (they end the path).
#pragma once

#include "scene/scene.h"

namespace dp::pathspace {

// SCENE_FORMAT.md default 0.05 (as Gruson 2018). The reference G-PT code uses 0.001 and
// the G-VCM paper 0.01; the integrator exposes it as `shift_threshold`.
constexpr float kDefaultShiftThreshold = 0.05f;
// Phong exponents above this are glossy (roughness sqrt(2/(2+n)) would call n = 100
// connectable at any threshold below 0.14).
constexpr float kPhongExponentThreshold = 100.0f;

inline bool is_connectable(const scene::Bsdf* bsdf, float threshold) {
  if (!bsdf) return true;
  if (bsdf->is_purely_delta()) return false;
  if (bsdf->phong_exponent() > kPhongExponentThreshold) return false;
  return !(bsdf->roughness() < threshold);
}

// Classification of a light point sampled by NEE (the BSDF of the emitter's shape).
bool is_connectable(const scene::Scene& scene, const scene::Emitter* emitter, float threshold);

}  // namespace dp::pathspace
