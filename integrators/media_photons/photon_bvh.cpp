#include "integrators/media_photons/photon_bvh.h"

#include <algorithm>

namespace dp::integrators {

void PhotonBvh::build(std::vector<MediumPhoton> photons) {
  m_photons = std::move(photons);
  m_nodes.clear();
  if (m_photons.empty()) return;
  m_nodes.reserve(2 * (m_photons.size() / kLeafSize + 1));
  build_node(0, uint32_t(m_photons.size()), 0);
}

void PhotonBvh::release() {
  m_nodes = {};
  m_photons = {};
}

uint32_t PhotonBvh::build_node(uint32_t first, uint32_t count, int depth) {
  const uint32_t index = uint32_t(m_nodes.size());
  m_nodes.emplace_back();
  Bounds3 b;
  for (uint32_t k = first; k < first + count; ++k) b.expand(m_photons[k].p);
  m_nodes[index].lo = b.lo;
  m_nodes[index].hi = b.hi;
  // Median splits halve the count: depth stays below log2(2^32 / kLeafSize) < kStack / 2,
  // the traversal stack's bound (it holds at most one pending sibling per level).
  if (count <= kLeafSize || depth >= kStack / 2 - 2) {
    m_nodes[index].first = first;
    m_nodes[index].count = count;
    return index;
  }
  const Vec3 ext = b.hi - b.lo;
  int axis = 0;
  if (ext.y() > ext[axis]) axis = 1;
  if (ext.z() > ext[axis]) axis = 2;
  const uint32_t half = count / 2;
  auto begin = m_photons.begin() + first;
  std::nth_element(begin, begin + half, begin + count,
                   [axis](const MediumPhoton& a, const MediumPhoton& c) { return a.p[axis] < c.p[axis]; });
  build_node(first, half, depth + 1);
  const uint32_t right = build_node(first + half, count - half, depth + 1);
  m_nodes[index].right = right;
  return index;
}

}  // namespace dp::integrators
