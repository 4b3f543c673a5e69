#include "gradients/gradient_buffers.h"

#include <algorithm>

#include "core/error.h"

namespace dp::gradients {

GradientBuffers::GradientBuffers(int width, int height)
    : m_w(width),
      m_h(height),
      m_primal(size_t(width) * size_t(height), Rgbd::Zero()),
      m_dx(m_primal),
      m_dy(m_primal),
      m_direct(m_primal),
      m_count(m_primal.size(), 0) {}

void GradientBuffers::merge(const GradientBuffers& o) {
  DP_CHECK(o.m_w == m_w && o.m_h == m_h, "GradientBuffers::merge: size mismatch");
  for (size_t i = 0; i < m_primal.size(); ++i) {
    m_primal[i] += o.m_primal[i];
    m_dx[i] += o.m_dx[i];
    m_dy[i] += o.m_dy[i];
    m_direct[i] += o.m_direct[i];
    m_count[i] += o.m_count[i];
  }
}

void GradientBuffers::clear() {
  for (auto* v : {&m_primal, &m_dx, &m_dy, &m_direct}) std::fill(v->begin(), v->end(), Rgbd::Zero());
  std::fill(m_count.begin(), m_count.end(), 0);
}

core::RawImage GradientBuffers::to_raw() const {
  core::RawImage raw;
  raw.width = m_w;
  raw.height = m_h;
  raw.sums = {{"primal", m_primal}, {"dx", m_dx}, {"dy", m_dy}, {"direct", m_direct}};
  raw.counts = {{"spp", m_count}};
  return raw;
}

GradientBuffers GradientBuffers::from_raw(const core::RawImage& raw) {
  GradientBuffers b;
  b.m_w = raw.width;
  b.m_h = raw.height;
  b.m_primal = raw.sum("primal");
  b.m_dx = raw.sum("dx");
  b.m_dy = raw.sum("dy");
  b.m_direct = raw.sum("direct");
  b.m_count = raw.count("spp");
  return b;
}

core::Image GradientBuffers::normalized(const std::vector<Rgbd>& sums) const {
  core::Image img(m_w, m_h);
  for (size_t i = 0; i < sums.size(); ++i)
    if (m_count[i] > 0) img[i] = (sums[i] / double(m_count[i])).cast<float>();
  return img;
}

}  // namespace dp::gradients
