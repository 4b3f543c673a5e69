#include "core/image.h"

#include "core/error.h"

namespace dp::core {

Image& Image::operator+=(const Image& o) {
  DP_CHECK(same_size(o), "image size mismatch");
  for (size_t i = 0; i < m_pixels.size(); ++i) m_pixels[i] += o.m_pixels[i];
  return *this;
}

Image& Image::operator-=(const Image& o) {
  DP_CHECK(same_size(o), "image size mismatch");
  for (size_t i = 0; i < m_pixels.size(); ++i) m_pixels[i] -= o.m_pixels[i];
  return *this;
}

Image& Image::operator*=(float s) {
  for (auto& p : m_pixels) p *= s;
  return *this;
}

Rgbd Image::mean() const {
  Rgbd sum = Rgbd::Zero();
  for (const auto& p : m_pixels) sum += p.cast<double>();
  return m_pixels.empty() ? sum : Rgbd(sum / double(m_pixels.size()));
}

size_t Image::count_nonfinite() const {
  size_t n = 0;
  for (const auto& p : m_pixels) n += is_finite(p) ? 0 : 1;
  return n;
}

size_t Image::zero_nonfinite() {
  size_t n = 0;
  for (auto& p : m_pixels) {
    if (is_finite(p)) continue;
    ++n;
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(p[c])) p[c] = 0.0f;
  }
  return n;
}

}  // namespace dp::core
