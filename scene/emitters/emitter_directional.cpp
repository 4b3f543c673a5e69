// Directional light (delta in direction): every point receives `irradiance` on a
// surface perpendicular to the light. sample_direct returns wi = -direction, pdf 1,
// radiance = irradiance (emitter.h contract) and a far point outside the scene's
// bounding sphere for shadow rays.
#include "core/error.h"
#include "scene/emitters/emitter.h"

namespace dp::scene {

DirectionalEmitter::DirectionalEmitter(const Vec3& direction, const Rgb& irradiance) : m_irradiance(irradiance) {
  const float len = direction.norm();
  if (!(len > 0.0f) || !std::isfinite(len)) throw ValueError("directional light: direction must be a non-zero vector");
  m_direction = direction / len;
}

void DirectionalEmitter::prepare(const Bounds3& scene_bounds) {
  const float r = 0.5f * scene_bounds.diagonal();
  m_scene_radius = r > 0.0f && std::isfinite(r) ? r : 1.0f;
}

DirectSample DirectionalEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  (void)u;
  DirectSample s;
  s.wi = -m_direction;
  // Any point of the scene is within 2 radii of any other, so this is outside it.
  s.p = ref + s.wi * (2.0f * m_scene_radius);
  s.n = Vec3::Zero();
  s.dist = kInfinity;
  s.radiance = m_irradiance;
  s.pdf = 1.0f;
  s.delta = true;
  return s;
}

// Power crossing the scene: irradiance times the bounding disk's area (pbrt-v3
// DistantLight::Power).
Rgb DirectionalEmitter::power() const { return m_irradiance * (kPi * m_scene_radius * m_scene_radius); }

}  // namespace dp::scene
