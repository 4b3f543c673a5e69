// Pinhole perspective camera (camera.h). Camera frame: n = forward,
// s = right = normalize(forward x up), t = down = n x s, so that raster x grows along s
// and raster y (row 0 = top) grows along t. The image plane at distance 1 spans
// [-tan_half_x, tan_half_x] x [-tan_half_y, tan_half_y]; the fov is the full angle
// along fov_axis and the other half-extent follows from the aspect ratio.
#include "scene/camera.h"

#include <cmath>

#include "core/error.h"

namespace dp::scene {

PerspectiveCamera::PerspectiveCamera(const CameraDesc& desc) : m_desc(desc) {
  if (desc.width <= 0 || desc.height <= 0)
    throw ValueError("camera: resolution must be positive, got " + std::to_string(desc.width) + "x" +
                     std::to_string(desc.height));
  if (!(desc.fov_deg > 0.0f) || !(desc.fov_deg < 180.0f))
    throw ValueError("camera: fov must be in (0, 180) degrees, got " + std::to_string(desc.fov_deg));
  const Vec3 fwd = desc.look_at - desc.position;
  if (!(fwd.norm() > 0.0f) || !fwd.allFinite()) throw ValueError("camera: look_at equals position");
  const Vec3 n = fwd.normalized();
  const Vec3 right = n.cross(desc.up);
  if (!(right.norm() > 1e-6f * desc.up.norm()) || !right.allFinite())
    throw ValueError("camera: up vector is zero or parallel to the view direction");
  const Vec3 s = right.normalized();
  m_frame = Frame(s, n.cross(s), n);
  const float tan_half = std::tan(0.5f * deg_to_rad(desc.fov_deg));
  const float aspect = float(desc.width) / float(desc.height);
  if (desc.fov_axis_x) {
    m_tan_half_x = tan_half;
    m_tan_half_y = tan_half / aspect;
  } else {
    m_tan_half_y = tan_half;
    m_tan_half_x = tan_half * aspect;
  }
}

Ray PerspectiveCamera::generate_ray(const Vec2& raster) const {
  const float x = (2.0f * raster.x() / float(m_desc.width) - 1.0f) * m_tan_half_x;
  const float y = (2.0f * raster.y() / float(m_desc.height) - 1.0f) * m_tan_half_y;
  Ray r;
  r.o = m_desc.position;
  r.d = m_frame.to_world(Vec3(x, y, 1.0f)).normalized();
  r.tmin = 0;
  r.tmax = kInfinity;
  return r;
}

std::optional<Vec2> PerspectiveCamera::raster_of(const Vec3& p) const {
  const Vec3 local = m_frame.to_local(p - m_desc.position);
  if (!(local.z() > 0.0f)) return std::nullopt;
  const float x = local.x() / local.z(), y = local.y() / local.z();
  const Vec2 raster((x / m_tan_half_x + 1.0f) * 0.5f * float(m_desc.width),
                    (y / m_tan_half_y + 1.0f) * 0.5f * float(m_desc.height));
  if (!(raster.x() >= 0.0f && raster.x() < float(m_desc.width) && raster.y() >= 0.0f &&
        raster.y() < float(m_desc.height)))
    return std::nullopt;
  return raster;
}

// Uniform raster position -> uniform point on the image plane at distance 1 (density
// 1 / A_img); dA = dω r^2 / cos θ with r = 1 / cos θ gives dA/dω = 1 / cos^3 θ
// (Veach 1997, Sec. 10.3; pbrt-v3 Sec. 16.1.1).
float PerspectiveCamera::pdf_direction(const Vec3& w) const {
  const Vec3 local = m_frame.to_local(w);
  const float c = local.z();
  if (!(c > 0.0f)) return 0.0f;
  const float x = local.x() / c, y = local.y() / c;
  if (std::abs(x) > m_tan_half_x || std::abs(y) > m_tan_half_y) return 0.0f;
  const float area = 4.0f * m_tan_half_x * m_tan_half_y;
  return 1.0f / (area * c * c * c);
}

}  // namespace dp::scene
