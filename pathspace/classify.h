// Vertex classification for shift mappings (Kettunen et al. 2015, Sec. 5; ALGORITHMS.md).
// A surface vertex is CONNECTABLE ("diffuse") when the lowest roughness of its BSDF's
// non-delta components exceeds the threshold; otherwise it is glossy/specular and shifts
// copy its half vector. BSDFs with only Dirac lobes report roughness 0 and are never
// connectable. A vertex without a BSDF (a pure emitter), an environment vertex and
// non-area light points are connectable (they end the path).
#pragma once

#include "scene/scene.h"

namespace dp::pathspace {

// Reference G-PT default (mmanzi/gradientdomain-mitsuba, gpt.cpp): 0.001. The G-VCM paper
// uses 0.01 and Gruson 2018 0.05; the integrator exposes it as `shift_threshold`.
constexpr float kDefaultShiftThreshold = 0.001f;

inline bool is_connectable(const scene::Bsdf* bsdf, float threshold) {
  if (!bsdf) return true;
  if (bsdf->is_purely_delta()) return false;
  return bsdf->roughness() > threshold;
}

// Classification of a light point sampled by NEE (the BSDF of the emitter's shape).
bool is_connectable(const scene::Scene& scene, const scene::Emitter* emitter, float threshold);

}  // namespace dp::pathspace
