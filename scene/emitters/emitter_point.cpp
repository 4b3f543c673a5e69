// Point and spot lights (delta in position). Radiance returned by sample_direct is
// the irradiance-producing quantity intensity / d^2 (emitter.h contract), pdf = 1.
//
// Spot falloff: full intensity inside the falloff_start cone, zero outside the cutoff
// cone, and a smoothstep of cos(theta) in between, as in pbrt-v4's SpotLight (pbrt-v3
// used the 4th power of the same linear ramp; smoothstep has a C1 edge):
//   f(theta) = smoothstep((cos theta - cos cutoff) / (cos falloff_start - cos cutoff)).
// Power: Phi = I * 2 pi * [(1 - cos falloff_start) + (cos falloff_start - cos cutoff) / 2],
// exact because the smoothstep integrates to 1/2 over its ramp.
#include <algorithm>

#include "core/error.h"
#include "scene/emitters/emitter.h"

namespace dp::scene {

namespace {

DirectSample delta_position_sample(const Vec3& ref, const Vec3& position) {
  DirectSample s;
  s.p = position;
  s.n = Vec3::Zero();
  s.delta = true;
  const Vec3 d = position - ref;
  const float dist2 = d.squaredNorm();
  if (!(dist2 > 0.0f)) return s;  // ref at the light: pdf 0, nothing arrives
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  s.pdf = 1.0f;
  return s;
}

}  // namespace

DirectSample PointEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  (void)u;
  DirectSample s = delta_position_sample(ref, m_position);
  if (s.pdf > 0.0f) s.radiance = m_intensity / (s.dist * s.dist);
  return s;
}

SpotEmitter::SpotEmitter(const Vec3& position, const Vec3& direction, const Rgb& intensity, float cutoff_deg,
                         float falloff_start_deg)
    : m_position(position), m_intensity(intensity) {
  const float len = direction.norm();
  if (!(len > 0.0f) || !std::isfinite(len)) throw ValueError("spot light: direction must be a non-zero vector");
  if (!(cutoff_deg > 0.0f) || !(cutoff_deg <= 180.0f))
    throw ValueError("spot light: cutoff must be in (0, 180] degrees");
  if (!(falloff_start_deg >= 0.0f)) throw ValueError("spot light: falloff_start must be >= 0 degrees");
  m_frame = Frame::from_normal(direction / len);
  m_cos_cutoff = std::cos(deg_to_rad(cutoff_deg));
  // falloff_start beyond the cutoff means a hard edge at the cutoff.
  m_cos_falloff_start = std::cos(deg_to_rad(std::min(falloff_start_deg, cutoff_deg)));
}

Rgb SpotEmitter::intensity(const Vec3& w) const {
  const float c = m_frame.n.dot(w);
  if (c < m_cos_cutoff) return Rgb::Zero();
  if (c >= m_cos_falloff_start) return m_intensity;
  const float x = std::clamp((c - m_cos_cutoff) / (m_cos_falloff_start - m_cos_cutoff), 0.0f, 1.0f);
  return m_intensity * (x * x * (3.0f - 2.0f * x));
}

DirectSample SpotEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  (void)u;
  DirectSample s = delta_position_sample(ref, m_position);
  if (s.pdf > 0.0f) s.radiance = intensity(-s.wi) / (s.dist * s.dist);
  return s;
}

Rgb SpotEmitter::power() const {
  return m_intensity * (2.0f * kPi) * ((1.0f - m_cos_falloff_start) + 0.5f * (m_cos_falloff_start - m_cos_cutoff));
}

}  // namespace dp::scene
