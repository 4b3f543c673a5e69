// Bitmap and checkerboard textures (contract in texture.h).
// Bitmap lookup: texel (i, j) (j = image row from the top) has its centre at
// uv = ((i + 0.5) / W, 1 - (j + 0.5) / H), i.e. uv (0, 0) is the bottom-left corner of
// the image (Mitsuba / OBJ convention). Bilinear interpolation between the four
// nearest texel centres, repeat wrapping in both directions.
#include "scene/texture.h"

#include "core/error.h"
#include "core/image_io.h"

namespace dp::scene {

namespace {
int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
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
  const int x0 = wrap(int(fx), w), x1 = wrap(int(fx) + 1, w);
  const int y0 = wrap(int(fy), h), y1 = wrap(int(fy) + 1, h);
  return (1.0f - ty) * ((1.0f - tx) * m_image(x0, y0) + tx * m_image(x1, y0)) +
         ty * ((1.0f - tx) * m_image(x0, y1) + tx * m_image(x1, y1));
}

Rgb CheckerboardTexture::eval(const Vec2& uv) const {
  const long long a = (long long)std::floor(double(uv.x()) * double(m_scale.x()));
  const long long b = (long long)std::floor(double(uv.y()) * double(m_scale.y()));
  return ((a + b) % 2 == 0) ? m_c0 : m_c1;
}

}  // namespace dp::scene
