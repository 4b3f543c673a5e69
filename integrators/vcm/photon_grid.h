// Hashed uniform grid over the light vertices of one VCM iteration (range queries of a
// fixed radius r). Cells are 2r wide, so the points within r of a query lie in the
// 2x2x2 block of cells nearest to it; cells are hashed into a table of about one bucket
// per point and bucketed by a counting sort (deterministic, no per-cell allocation).
// Hash collisions only add candidates: every candidate's distance is tested. Points are
// kept in bucket order and queries report that order's slots, so a caller that stores
// its per-point records in the same order (order()) reads them contiguously.
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
  void release();  // frees every array (empty grid)
  bool empty() const { return m_points.empty(); }
  float radius() const { return m_radius; }
  // order()[k] = the input index of the point in slot k.
  const std::vector<uint32_t>& order() const { return m_index; }
  // fn(k) for every slot k whose point lies within r of q, in a fixed order.
  template <class Fn>
  void query(const Vec3& q, Fn&& fn) const {
    query(q, m_radius, fn);
  }
  // The same within `r` (any r > 0; above the build radius more cells are visited, each
  // bucket once). G-PM's kernels follow each camera path's pixel footprint.
  template <class Fn>
  void query(const Vec3& q, float r, Fn&& fn) const {
    if (m_points.empty() || !(r > 0.0f)) return;
    if (r > m_radius) return query_wide(q, r, fn);
    const Vec3 c = (q - m_min) * m_inv_cell;
    int base[3], step[3];
    for (int k = 0; k < 3; ++k) {
      const float f = std::clamp(std::floor(c[k]), -1e9f, 1e9f);  // no int overflow far away
      base[k] = int(f);
      step[k] = c[k] - f < 0.5f ? -1 : 1;
    }
    // The 8 bucket ranges first: independent loads the CPU overlaps (the query is
    // bound by these cache misses, not by arithmetic).
    // Two of the cells may share a bucket (a hash collision): each bucket is visited once.
    uint32_t bucket[8], begin[8], end[8];
    for (int i = 0; i < 8; ++i) {
      bucket[i] = hash(base[0] + (i & 1) * step[0], base[1] + ((i >> 1) & 1) * step[1], base[2] + (i >> 2) * step[2]);
      begin[i] = m_start[bucket[i]];
      end[i] = m_start[bucket[i] + 1];
      for (int k = 0; k < i; ++k)
        if (bucket[k] == bucket[i]) end[i] = begin[i];
    }
    const float r2 = r * r;
    for (int i = 0; i < 8; ++i)
      for (uint32_t k = begin[i]; k < end[i]; ++k)
        if ((m_points[k] - q).squaredNorm() <= r2) fn(k);
  }

 private:
  template <class Fn>
  void query_wide(const Vec3& q, float r, Fn&& fn) const {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = int(std::clamp(std::floor((q[k] - r - m_min[k]) * m_inv_cell), -1e9f, 1e9f));
      hi[k] = int(std::clamp(std::floor((q[k] + r - m_min[k]) * m_inv_cell), -1e9f, 1e9f));
    }
    // Distinct buckets of the cell block (hash collisions would report points twice).
    std::vector<uint32_t> buckets;
    const int64_t cells = int64_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (cells > int64_t(m_mask) + 1) {  // more cells than buckets: scan every bucket
      buckets.resize(size_t(m_mask) + 1);
      for (uint32_t b = 0; b <= m_mask; ++b) buckets[b] = b;
    } else {
      for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int x = lo[0]; x <= hi[0]; ++x) buckets.push_back(hash(x, y, z));
      std::sort(buckets.begin(), buckets.end());
      buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
    }
    const float r2 = r * r;
    for (uint32_t b : buckets)
      for (uint32_t k = m_start[b]; k < m_start[b + 1]; ++k)
        if ((m_points[k] - q).squaredNorm() <= r2) fn(k);
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
