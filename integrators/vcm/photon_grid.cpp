#include "integrators/vcm/photon_grid.h"

#include <algorithm>
#include <cmath>

namespace dp::integrators {

void PhotonGrid::build(const std::vector<Vec3>& points, float radius) {
  m_points.clear();
  m_index.clear();
  m_start.clear();
  m_radius = radius;
  if (points.empty() || !(radius > 0.0f)) return;
  m_min = points[0];
  for (const Vec3& p : points) m_min = m_min.cwiseMin(p);
  m_inv_cell = 0.5f / radius;
  uint32_t size = 1;
  while (size < points.size() && size < (1u << 30)) size <<= 1;
  m_mask = size - 1;
  std::vector<uint32_t> cell(points.size());
  m_start.assign(size_t(size) + 1, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 c = (points[i] - m_min) * m_inv_cell;
    auto cell_of = [](float v) { return int(std::clamp(std::floor(v), -1e9f, 1e9f)); };
    cell[i] = hash(cell_of(c.x()), cell_of(c.y()), cell_of(c.z()));
    ++m_start[cell[i] + 1];
  }
  for (uint32_t h = 0; h < size; ++h) m_start[h + 1] += m_start[h];
  std::vector<uint32_t> fill(m_start.begin(), m_start.end() - 1);
  m_index.resize(points.size());
  m_points.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const uint32_t k = fill[cell[i]]++;
    m_index[k] = uint32_t(i);
    m_points[k] = points[i];
  }
}

void PhotonGrid::release() {
  m_points = {};
  m_index = {};
  m_start = {};
}

}  // namespace dp::integrators
