// Hashed uniform grid over the light vertices of one VCM iteration (range queries of a
// fixed radius r). Cells are 2r wide, so the points within r of a query lie in the
// 2x2x2 block of cells nearest to it; cells are hashed into a table of about one bucket
// per point and bucketed by a counting sort (deterministic, no per-cell allocation).
// Hash collisions only add candidates: every candidate's distance is tested.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace dp::integrators {

class PhotonGrid {
 public:
  // Indexes points[0 .. n-1] for queries of radius r > 0 (points are copied).
  void build(const std::vector<Vec3>& points, float radius);
  bool empty() const { return m_points.empty(); }
  // fn(i) for every indexed point i with |p_i - q| <= r, in a fixed order.
  template <class Fn>
  void query(const Vec3& q, Fn&& fn) const {
    if (m_points.empty()) return;
    const Vec3 c = (q - m_min) * m_inv_cell;
    int base[3], step[3];
    for (int k = 0; k < 3; ++k) {
      const float f = std::clamp(std::floor(c[k]), -1e9f, 1e9f);  // no int overflow far away
      base[k] = int(f);
      step[k] = c[k] - f < 0.5f ? -1 : 1;
    }
    const float r2 = m_radius * m_radius;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const uint32_t h = hash(base[0] + dx * step[0], base[1] + dy * step[1], base[2] + dz * step[2]);
          for (uint32_t k = m_start[h]; k < m_start[h + 1]; ++k)
            if ((m_points[k] - q).squaredNorm() <= r2) fn(m_index[k]);
        }
  }

 private:
  uint32_t hash(int x, int y, int z) const {
    return ((uint32_t(x) * 73856093u) ^ (uint32_t(y) * 19349663u) ^ (uint32_t(z) * 83492791u)) & m_mask;
  }
  float m_radius = 0, m_inv_cell = 0;
  Vec3 m_min{0, 0, 0};
  uint32_t m_mask = 0;
  std::vector<uint32_t> m_start, m_index;
  std::vector<Vec3> m_points;  // in bucket order
};

}  // namespace dp::integrators
