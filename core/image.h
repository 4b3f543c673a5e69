// Float RGB image, row-major, row 0 = top row. Pixel values are linear RGB.
#pragma once

#include <vector>

#include "core/math.h"

namespace dp::core {

class Image {
 public:
  Image() = default;
  Image(int width, int height, const Rgb& fill = Rgb::Zero())
      : m_width(width), m_height(height), m_pixels(size_t(width) * size_t(height), fill) {}

  int width() const { return m_width; }
  int height() const { return m_height; }
  size_t size() const { return m_pixels.size(); }
  bool empty() const { return m_pixels.empty(); }
  bool same_size(const Image& o) const { return m_width == o.m_width && m_height == o.m_height; }

  Rgb& operator()(int x, int y) { return m_pixels[size_t(y) * size_t(m_width) + size_t(x)]; }
  const Rgb& operator()(int x, int y) const { return m_pixels[size_t(y) * size_t(m_width) + size_t(x)]; }
  Rgb& operator[](size_t i) { return m_pixels[i]; }
  const Rgb& operator[](size_t i) const { return m_pixels[i]; }
  std::vector<Rgb>& pixels() { return m_pixels; }
  const std::vector<Rgb>& pixels() const { return m_pixels; }

  void fill(const Rgb& c) { std::fill(m_pixels.begin(), m_pixels.end(), c); }
  Image& operator+=(const Image& o);
  Image& operator-=(const Image& o);
  Image& operator*=(float s);
  // Mean over all pixels (double accumulation).
  Rgbd mean() const;
  // Number of pixels with a NaN or Inf channel.
  size_t count_nonfinite() const;
  // Replace non-finite channels by 0; returns how many pixels were touched.
  size_t zero_nonfinite();

 private:
  int m_width = 0, m_height = 0;
  std::vector<Rgb> m_pixels;
};

}  // namespace dp::core
