// Accumulators of a gradient-domain render on the 4-neighbour forward-difference grid:
// primal sums, dx sums (pair (x,y) -> (x+1,y)), dy sums (pair (x,y) -> (x,y+1)), a
// directly-visible-emitter layer and per-pixel sample counts, all in double. Each thread
// owns one full-image buffer (neighbouring pixels' pairs cross tile borders) and the
// buffers are merged at the end. Normalization divides pixel (x,y)'s sums by its own
// sample count: both pixels of a pair must have rendered the same number of samples
// (G-PT renders whole passes).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/raw_image.h"

namespace dp::gradients {

class GradientBuffers {
 public:
  GradientBuffers() = default;
  GradientBuffers(int width, int height);
  int width() const { return m_w; }
  int height() const { return m_h; }

  void add_primal(int x, int y, const Rgbd& v) { m_primal[index(x, y)] += v; }
  void add_dx(int x, int y, const Rgbd& v) { m_dx[index(x, y)] += v; }
  void add_dy(int x, int y, const Rgbd& v) { m_dy[index(x, y)] += v; }
  void add_direct(int x, int y, const Rgbd& v) { m_direct[index(x, y)] += v; }
  void add_samples(int x, int y, int64_t n) { m_count[index(x, y)] += n; }
  void merge(const GradientBuffers& other);
  void clear();  // every sum and count back to zero (same size)

  int64_t samples(int x, int y) const { return m_count[index(x, y)]; }
  // Raw (unnormalized) sums, e.g. to inspect what one sample splatted.
  const Rgbd& primal_sum(int x, int y) const { return m_primal[index(x, y)]; }
  const Rgbd& dx_sum(int x, int y) const { return m_dx[index(x, y)]; }
  const Rgbd& dy_sum(int x, int y) const { return m_dy[index(x, y)]; }
  core::Image primal() const { return normalized(m_primal); }
  core::Image dx() const { return normalized(m_dx); }
  core::Image dy() const { return normalized(m_dy); }
  core::Image direct() const { return normalized(m_direct); }
  // The raw sums "primal", "dx", "dy", "direct" and the count "spp" (render --partial),
  // and back: from_raw throws dp::ValueError naming a missing buffer.
  core::RawImage to_raw() const;
  static GradientBuffers from_raw(const core::RawImage& raw);

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(m_w) + size_t(x); }
  core::Image normalized(const std::vector<Rgbd>& sums) const;
  int m_w = 0, m_h = 0;
  std::vector<Rgbd> m_primal, m_dx, m_dy, m_direct;
  std::vector<int64_t> m_count;
};

}  // namespace dp::gradients
