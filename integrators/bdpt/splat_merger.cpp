#include "integrators/bdpt/splat_merger.h"

namespace dp::integrators {

void SplatMerger::apply(size_t tile) {
  for (const Splat& s : m_pending[tile]) m_image[size_t(s.pixel)] += s.value.cast<double>();
  std::vector<Splat>().swap(m_pending[tile]);
}

void SplatMerger::submit(int tile, std::vector<Splat>&& splats) {
  const std::lock_guard<std::mutex> lock(m_mutex);
  m_pending[size_t(tile)] = std::move(splats);
  m_ready[size_t(tile)] = 1;
  while (m_next < m_ready.size() && m_ready[m_next]) apply(m_next++);
}

void SplatMerger::finish_pass() {
  const std::lock_guard<std::mutex> lock(m_mutex);
  for (size_t i = m_next; i < m_ready.size(); ++i)
    if (m_ready[i]) apply(i);
  std::fill(m_ready.begin(), m_ready.end(), 0);
  m_next = 0;
}

}  // namespace dp::integrators
