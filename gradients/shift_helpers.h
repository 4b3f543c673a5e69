// Small per-vertex helpers shared by the shift mappings (reconnection_shift.cpp,
// manifold_shift.cpp): side consistency of an offset vertex's incoming direction and the
// scattering record of an offset vertex.
#pragma once

#include "pathspace/scatter.h"

namespace dp::gradients {

inline Vec3d d3(const Vec3& v) { return v.cast<double>(); }

// The vertex's sampled lobe crosses the surface (wi and wo on opposite sides, local frame).
inline bool is_refraction(const pathspace::Vertex& v) { return v.wi.z() * v.wo.z() < 0.0f; }

// The offset vertex's incoming direction lies on the side its local frame says it does.
inline bool wi_consistent(const pathspace::Vertex& v) {
  return pathspace::consistent_side(v.hit, v.hit.shading.to_world(v.wi), v.wi.z());
}

// Sets the scattering record of offset vertex v toward local direction wo (lobe choice
// and Russian roulette copied from the base vertex: RR follows the base, Kettunen 2015,
// Sec. 5.3).
inline void set_scatter(pathspace::Vertex& v, const pathspace::Vertex& base, const Vec3& wo, const Vec3& wo_world,
                        const Rgb& f_cos, double pdf) {
  v.lobe = base.lobe;
  v.u_lobe = base.u_lobe;
  v.eta = base.eta;
  v.rr = base.rr;
  v.wo = wo;
  v.wo_world = wo_world;
  v.f_cos = f_cos;
  v.pdf = pdf;
}

}  // namespace dp::gradients
