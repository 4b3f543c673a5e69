// Environment emitter: constant radiance, or a latitude-longitude (equirectangular)
// map importance-sampled by luminance * sin(theta).
//
// Lat-long mapping (Mitsuba's `envmap`, y up, so Mitsuba scenes match). For a world
// direction w, the map-local direction is v = to_world^-1 w and
//   u = atan2(v.x, -v.z) / (2 pi)  (wrapped to [0, 1)),   v_tex = acos(v.y) / pi,
// i.e. phi = 2 pi u, theta = pi v_tex and
//   v = (sin phi sin theta, cos theta, -cos phi sin theta).
// Pixel (i, j) covers u in [i, i+1)/W, v_tex in [j, j+1)/H; row 0 (top) is the +y pole,
// the image's horizontal centre column looks along +z, its left edge along -z.
// Lookup is nearest-pixel (Mitsuba filters bilinearly): the sampling density is then
// exactly proportional to luminance * sin(theta) of what the renderer evaluates, so a
// small bright sun is sampled with zero variance in its own pixel.
//
// Densities: Distribution2D gives pdf_uv over [0,1)^2. With dω = sin θ dθ dφ =
// 2 π² sin θ du dv, the solid-angle density is pdf_uv / (2 π² sin θ) (pbrt-v3
// Sec. 14.2.4, Eq. 14.7). The constant emitter samples the sphere uniformly, 1 / (4π).
#include <algorithm>
#include <cmath>

#include "core/distribution.h"
#include "core/error.h"
#include "core/warp.h"
#include "scene/emitters/emitter.h"

namespace dp::scene {

namespace {

Vec3 direction_of_uv(const Vec2& uv, float& sin_theta) {
  const float phi = 2.0f * kPi * uv.x(), theta = kPi * uv.y();
  sin_theta = std::sin(theta);
  return Vec3(std::sin(phi) * sin_theta, std::cos(theta), -std::cos(phi) * sin_theta);
}

Vec2 uv_of_direction(const Vec3& v) {
  float u = std::atan2(v.x(), -v.z()) * kInv2Pi;
  if (u < 0.0f) u += 1.0f;
  if (!(u < 1.0f)) u = 0.0f;
  return Vec2(u, std::acos(std::clamp(v.y(), -1.0f, 1.0f)) * kInvPi);
}

}  // namespace

EnvironmentEmitter::EnvironmentEmitter(const Rgb& radiance) : m_radiance(radiance) {
  if (!is_finite(radiance) || (radiance < 0.0f).any())
    throw ValueError("environment: radiance must be finite and non-negative");
}

EnvironmentEmitter::EnvironmentEmitter(core::Image latlong, const Mat3& to_world, float scale)
    : m_map(std::move(latlong)), m_to_world(to_world), m_scale(scale) {
  if (m_map.empty()) throw ValueError("environment: empty lat-long image");
  if (!(scale >= 0.0f) || !std::isfinite(scale)) throw ValueError("environment: scale must be finite and >= 0");
  // Directions are mapped with to_world^-1 = to_world^T and the pdf has no Jacobian
  // for the rotation, so the transform must be a rotation.
  if (!(to_world.transpose() * to_world).isIdentity(1e-3f) || !(to_world.determinant() > 0.0f))
    throw ValueError("environment: to_world must be a rotation (no scale, shear or mirror)");
  const int w = m_map.width(), h = m_map.height();
  std::vector<float> weights(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(h));
    for (int x = 0; x < w; ++x) {
      const Rgb& c = m_map(x, y);
      const float lum = is_finite(c) ? std::max(0.0f, luminance(c)) : 0.0f;
      weights[size_t(y) * size_t(w) + size_t(x)] = lum * sin_theta;
    }
  }
  m_dist = std::make_unique<core::Distribution2D>(weights, w, h);
}

EnvironmentEmitter::~EnvironmentEmitter() = default;

void EnvironmentEmitter::prepare(const Bounds3& scene_bounds) {
  const float r = 0.5f * scene_bounds.diagonal();
  m_scene_radius = r > 0.0f && std::isfinite(r) ? r : 1.0f;
}

Rgb EnvironmentEmitter::eval_direction(const Vec3& w) const {
  if (m_map.empty()) return m_radiance;
  const Vec2 uv = uv_of_direction(m_to_world.transpose() * w);
  const int x = std::clamp(int(uv.x() * float(m_map.width())), 0, m_map.width() - 1);
  const int y = std::clamp(int(uv.y() * float(m_map.height())), 0, m_map.height() - 1);
  const Rgb& c = m_map(x, y);
  return is_finite(c) ? Rgb(m_scale * c.max(0.0f)) : Rgb::Zero();
}

DirectSample EnvironmentEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  DirectSample s;
  s.n = Vec3::Zero();
  s.dist = kInfinity;
  if (m_map.empty()) {
    s.wi = core::warp::square_to_uniform_sphere(u);
    s.pdf = core::warp::square_to_uniform_sphere_pdf();
    s.radiance = m_radiance;
  } else {
    float pdf_uv = 0, sin_theta = 0;
    const Vec2 uv = m_dist->sample(u, pdf_uv);
    const Vec3 local = direction_of_uv(uv, sin_theta);
    s.wi = (m_to_world * local).normalized();
    if (!(pdf_uv > 0.0f) || !(sin_theta > 0.0f)) {
      s.p = ref + s.wi * (2.0f * m_scene_radius);
      return s;  // pole or zero-weight cell: failed sample, pdf 0
    }
    s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_theta);
    s.radiance = eval_direction(s.wi);
  }
  s.p = ref + s.wi * (2.0f * m_scene_radius);
  return s;
}

float EnvironmentEmitter::pdf_direct(const Vec3& ref, const Vec3& p, const Vec3& n, const Vec3& w) const {
  (void)ref;
  (void)p;
  (void)n;
  if (m_map.empty()) return core::warp::square_to_uniform_sphere_pdf();
  const Vec3 local = m_to_world.transpose() * w;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - sqr(std::clamp(local.y(), -1.0f, 1.0f))));
  if (!(sin_theta > 0.0f)) return 0.0f;
  return m_dist->pdf(uv_of_direction(local)) / (2.0f * kPi * kPi * sin_theta);
}

// Flux entering the scene's bounding sphere (radius R): every direction w illuminates
// the sphere's cross-section pi R^2, so Phi = pi R^2 * integral of L over the sphere of
// directions (= 4 pi^2 R^2 L for a constant environment).
Rgb EnvironmentEmitter::power() const {
  const float disk = kPi * m_scene_radius * m_scene_radius;
  if (m_map.empty()) return disk * 4.0f * kPi * m_radiance;
  const int w = m_map.width(), h = m_map.height();
  Rgbd total = Rgbd::Zero();
  for (int y = 0; y < h; ++y) {
    // Exact solid angle of the row: (cos theta0 - cos theta1) * 2 pi / W per pixel.
    const double row = (std::cos(kPiD * y / h) - std::cos(kPiD * (y + 1) / h)) * (2.0 * kPiD / w);
    for (int x = 0; x < w; ++x) {
      const Rgb& c = m_map(x, y);
      if (is_finite(c)) total += c.max(0.0f).cast<double>() * row;
    }
  }
  return disk * m_scale * total.cast<float>();
}

}  // namespace dp::scene
