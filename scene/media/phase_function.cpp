#include "scene/media/phase_function.h"

#include <algorithm>
#include <cmath>

namespace dp::scene {

namespace {
// Below this |g| the closed-form inverse loses its digits to cancellation (it divides by
// 2g); the isotropic warp is used instead. Its density differs from HG's by at most
// 3|g| relative, i.e. 3e-4: far below any test's resolution.
constexpr float kIsotropicG = 1e-4f;
}  // namespace

float HenyeyGreenstein::density(float cos_theta, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * cos_theta;
  return kInv4Pi * (1.0f - g * g) / (denom * std::sqrt(std::max(denom, 1e-12f)));
}

// CDF of mu = cos(theta): P(mu) = (1 - g^2) / (2g) [(1 + g^2 - 2 g mu)^(-1/2) - 1/(1 + g)];
// solving P(mu) = u gives 1 + g^2 - 2 g mu = ((1 - g^2) / (1 - g + 2 g u))^2.
float HenyeyGreenstein::sample_cos_theta(float u, float g) {
  if (std::abs(g) < kIsotropicG) return 1.0f - 2.0f * u;
  const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
  return std::clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

Vec3 HenyeyGreenstein::sample(const Vec3& wi, const Vec2& u) const {
  const float cos_t = sample_cos_theta(u.x(), m_g);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * kPi * u.y();
  const Frame frame = Frame::from_normal(wi);
  return frame.to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t)).normalized();
}

}  // namespace dp::scene
