// Bitmap and checkerboard textures (contract in texture.h).
// Bitmap lookup: texel (i, j) (j = image row from the top) has its centre at
// uv = ((i + 0.5) / W, 1 - (j + 0.5) / H), i.e. uv (0, 0) is the bottom-left corner of
// the image (Mitsuba / OBJ convention). Bilinear interpolation between the four
// nearest texel centres, repeat wrapping in both directions.
#include "scene/bsdf/texture.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image_io.h"

namespace dp::scene {

namespace {
// floor(x) mod n in [0, n), computed in double: uv times a texture's size or scale can
// be far outside int's range (a float-to-int conversion there is undefined behaviour).
int wrap(double x, int n) {
  if (!std::isfinite(x)) return 0;
  const double r = x - double(n) * std::floor(x / double(n));
  return std::clamp(int(r), 0, n - 1);
}
}  // namespace

BitmapTexture::BitmapTexture(const std::string& path, float scale, bool linear_ldr) {
  const bool exr = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".exr") == 0 ||
                                        path.compare(path.size() - 4, 4, ".EXR") == 0);
  m_image = exr ? core::read_exr(path) : core::read_ldr(path, linear_ldr);
  if (m_image.empty()) throw IoError("empty image", path);
  if (scale != 1.0f) m_image *= scale;
  init_stats();
}

BitmapTexture::BitmapTexture(core::Image image) : m_image(std::move(image)) {
  DP_CHECK(!m_image.empty(), "bitmap texture: empty image");
  init_stats();
}

void BitmapTexture::init_stats() {
  const Rgbd mean = m_image.mean();
  m_mean = mean.cast<float>();
  m_max = Rgb::Constant(-kInfinity);
  for (const Rgb& p : m_image.pixels()) m_max = m_max.max(p);
}

Rgb BitmapTexture::eval(const Vec2& uv) const {
  const int w = m_image.width(), h = m_image.height();
  // Continuous texel coordinates with integer values at texel centres; y from the top.
  const double x = double(uv.x()) * w - 0.5;
  const double y = (1.0 - double(uv.y())) * h - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const float tx = float(x - fx), ty = float(y - fy);
  const int x0 = wrap(fx, w), x1 = wrap(fx + 1.0, w);
  const int y0 = wrap(fy, h), y1 = wrap(fy + 1.0, h);
  return (1.0f - ty) * ((1.0f - tx) * m_image(x0, y0) + tx * m_image(x1, y0)) +
         ty * ((1.0f - tx) * m_image(x0, y1) + tx * m_image(x1, y1));
}

Rgb CheckerboardTexture::eval(const Vec2& uv) const {
  // Parity of floor(u su) + floor(v sv) without converting to an integer type (the
  // products can exceed any of them; beyond 2^53 every double is even).
  return (wrap(double(uv.x()) * double(m_scale.x()), 2) + wrap(double(uv.y()) * double(m_scale.y()), 2)) % 2 == 0 ? m_c0
                                                                                                              : m_c1;
}

}  // namespace dp::scene
