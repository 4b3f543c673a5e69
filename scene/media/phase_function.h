// The Henyey-Greenstein phase function (Henyey & Greenstein 1941); isotropic is g = 0.
// Contract:
//  * Directions are unit world vectors in the direction light TRAVELS along the camera
//    path's edges: `wi` is the direction of the ray arriving at the scattering point,
//    `wo` the direction of the ray leaving it, cos(theta) = dot(wi, wo). g > 0 scatters
//    forward (the peak is at wo = wi).
//  * eval() is a density in solid angle over the sphere of wo that integrates to 1, so
//    pdf() == eval() and sample()'s weight eval / pdf is exactly 1. It is symmetric:
//    p(wi, wo) = p(-wo, -wi), so the same value serves radiance and importance.
//  * The scattering coefficient sigma_s is not part of it (Gruson et al. 2018, Eq. 3:
//    a medium vertex contributes sigma_s * rho_p).
#pragma once

#include "core/math.h"
#include "scene/media/medium.h"

namespace dp::scene {

class HenyeyGreenstein {
 public:
  explicit HenyeyGreenstein(float g) : m_g(g) {}
  explicit HenyeyGreenstein(const PhaseFunctionDesc& desc)
      : m_g(desc.type == PhaseFunctionDesc::Type::hg ? desc.g : 0.0f) {}

  // p(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)).
  static float density(float cos_theta, float g);
  float eval(const Vec3& wi, const Vec3& wo) const { return density(wi.dot(wo), m_g); }
  float pdf(const Vec3& wi, const Vec3& wo) const { return eval(wi, wo); }
  // Inverts the CDF of cos(theta) in closed form; phi uniform. u in [0, 1)^2.
  Vec3 sample(const Vec3& wi, const Vec2& u) const;
  // The sampled cos(theta) alone (tests, and the frame-free part of sample()).
  static float sample_cos_theta(float u, float g);
  float g() const { return m_g; }

 private:
  float m_g;
};

}  // namespace dp::scene
