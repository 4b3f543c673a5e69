// Pinhole perspective camera with a one-pixel box filter. Raster space: x right,
// y down, pixel (i, j) covers [i, i+1) x [j, j+1); image row 0 is the top row.
#pragma once

#include <optional>

#include "core/math.h"

namespace dp::scene {

// Image size limits shared by the loaders: per side, and in total (every integrator holds a
// few double-precision RGB buffers per thread: 2^26 pixels, 8192 x 8192, is already
// several GB for the gradient-domain ones).
constexpr int kMaxImageSide = 65536;
constexpr long long kMaxImagePixels = 1LL << 26;
inline bool valid_image_size(long long w, long long h) {
  return w >= 1 && h >= 1 && w <= kMaxImageSide && h <= kMaxImageSide && w * h <= kMaxImagePixels;
}

struct CameraDesc {
  Vec3 position{0, 0, 0};
  Vec3 look_at{0, 0, -1};
  Vec3 up{0, 1, 0};
  float fov_deg = 45;
  bool fov_axis_x = false;  // fov measured along x (default: y)
  int width = 512, height = 512;
};

class PerspectiveCamera {
 public:
  explicit PerspectiveCamera(const CameraDesc& desc);
  const CameraDesc& desc() const { return m_desc; }
  int width() const { return m_desc.width; }
  int height() const { return m_desc.height; }
  const Vec3& position() const { return m_desc.position; }
  const Vec3& forward() const { return m_frame.n; }

  // Primary ray through raster position (x, y) (continuous, in pixels).
  Ray generate_ray(const Vec2& raster) const;
  // Raster position of the direction from the camera toward world point p, if it is
  // in front of the camera and inside the image.
  std::optional<Vec2> raster_of(const Vec3& p) const;
  // Solid-angle density of the primary direction w (unit, world) when the raster
  // position is uniform over the whole image: 1 / (A_img * cos^3 theta), with A_img
  // the image-plane area at distance 1. Per pixel, multiply by the pixel count.
  float pdf_direction(const Vec3& w) const;

 private:
  CameraDesc m_desc;
  Frame m_frame;  // s = right, t = down (raster y), n = forward
  float m_tan_half_x, m_tan_half_y;
};

}  // namespace dp::scene
