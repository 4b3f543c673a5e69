// RGB textures evaluated at surface uv. Bitmaps: 8-bit PNG/JPEG decoded sRGB -> linear
// (or EXR, linear), bilinear lookup, repeat wrapping, v = 0 at the bottom row.
#pragma once

#include <memory>
#include <string>

#include "core/image.h"
#include "core/math.h"

namespace dp::scene {

class Texture {
 public:
  virtual ~Texture() = default;
  virtual Rgb eval(const Vec2& uv) const = 0;
  virtual bool is_constant() const { return false; }
  // Average value (used for lobe-selection weights and albedo estimates).
  virtual Rgb mean() const = 0;
  virtual Rgb max() const = 0;
};

using TexturePtr = std::shared_ptr<const Texture>;

class ConstantTexture final : public Texture {
 public:
  explicit ConstantTexture(const Rgb& v) : m_value(v) {}
  Rgb eval(const Vec2&) const override { return m_value; }
  bool is_constant() const override { return true; }
  Rgb mean() const override { return m_value; }
  Rgb max() const override { return m_value; }

 private:
  Rgb m_value;
};

class BitmapTexture final : public Texture {
 public:
  // Throws dp::IoError if the file cannot be read. `scale` multiplies the texel values.
  explicit BitmapTexture(const std::string& path, float scale = 1.0f, bool linear_ldr = false);
  explicit BitmapTexture(core::Image image);
  Rgb eval(const Vec2& uv) const override;
  Rgb mean() const override { return m_mean; }
  Rgb max() const override { return m_max; }
  const core::Image& image() const { return m_image; }

 private:
  void init_stats();
  core::Image m_image;
  Rgb m_mean = Rgb::Zero(), m_max = Rgb::Zero();
};

// color0 where floor(u*scale.x) + floor(v*scale.y) is even, else color1.
class CheckerboardTexture final : public Texture {
 public:
  CheckerboardTexture(const Rgb& c0, const Rgb& c1, const Vec2& scale) : m_c0(c0), m_c1(c1), m_scale(scale) {}
  Rgb eval(const Vec2& uv) const override;
  Rgb mean() const override { return 0.5f * (m_c0 + m_c1); }
  Rgb max() const override { return m_c0.max(m_c1); }

 private:
  Rgb m_c0, m_c1;
  Vec2 m_scale;
};

inline TexturePtr constant_texture(const Rgb& v) { return std::make_shared<ConstantTexture>(v); }

}  // namespace dp::scene
