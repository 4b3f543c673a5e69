#include "integrators/plane/plane_bvh.h"

#include <algorithm>
#include <cmath>

namespace dp::integrators {

namespace {

// n equal parts of [a, b] of length >= `piece` (at most kMaxSplit); the k-th ends where
// the (k+1)-th starts (computed alike), the last at b exactly.
int split_count(float a, float b, float piece) {
  if (!(piece > 0.0f) || !std::isfinite(piece)) return 1;
  return std::clamp(int(std::floor((b - a) / piece)), 1, PlaneBvh::kMaxSplit);
}
float split_at(float a, float b, int k, int n) { return k == n ? b : a + (b - a) * float(k) / float(n); }

}  // namespace

PlaneBvh::Box PlaneBvh::piece_box(const Piece& p) const {
  const MediumPlane& pl = m_planes[p.plane];
  Bounds3 b;
  for (float u : {p.u0, p.u1})
    for (float v : {p.v0, p.v1}) b.expand(Vec3(pl.a0 + u * pl.w0 + v * pl.w1));
  Box box;
  box.lo = b.lo;
  box.hi = b.hi;
  box.pad = 1e-4f * std::max(b.hi.cwiseAbs().maxCoeff(), b.lo.cwiseAbs().maxCoeff()) + 1e-6f;
  return box;
}

void PlaneBvh::build(std::vector<MediumPlane> planes, float max_piece) {
  m_planes = std::move(planes);
  m_nodes.clear();
  m_pieces.clear();
  m_boxes.clear();
  if (m_planes.empty()) return;
  for (uint32_t i = 0; i < uint32_t(m_planes.size()); ++i) {
    const MediumPlane& pl = m_planes[i];
    const int n0 = split_count(pl.t0_begin, pl.t0_end, max_piece), n1 = split_count(0.0f, pl.t1_end, max_piece);
    for (int a = 0; a < n0; ++a)
      for (int b = 0; b < n1; ++b)
        m_pieces.push_back(Piece{i, split_at(pl.t0_begin, pl.t0_end, a, n0),
                                 split_at(pl.t0_begin, pl.t0_end, a + 1, n0), split_at(0.0f, pl.t1_end, b, n1),
                                 split_at(0.0f, pl.t1_end, b + 1, n1)});
  }
  m_boxes.resize(m_pieces.size());
  m_nodes.reserve(2 * (m_pieces.size() / kLeafSize + 1));
  build_node(0, uint32_t(m_pieces.size()), 0);
}

void PlaneBvh::release() {
  m_nodes = {};
  m_pieces = {};
  m_boxes = {};
  m_planes = {};
}

float PlaneBvh::clip(const Vec3& o, const Vec3& d, float w_max) const {
  if (m_nodes.empty()) return 0.0f;
  return grown_box_exit(m_nodes[0].lo, m_nodes[0].hi, 2.0f * m_nodes[0].pad, o, d, w_max);
}

uint32_t PlaneBvh::build_node(uint32_t first, uint32_t count, int depth) {
  const uint32_t index = uint32_t(m_nodes.size());
  m_nodes.emplace_back();
  Bounds3 b, mid;
  float pad = 0.0f;
  for (uint32_t k = first; k < first + count; ++k) {
    const Box box = piece_box(m_pieces[k]);
    b.expand(box.lo);
    b.expand(box.hi);
    mid.expand(Vec3(0.5f * (box.lo + box.hi)));
    pad = std::max(pad, box.pad);
  }
  m_nodes[index].lo = b.lo;
  m_nodes[index].hi = b.hi;
  m_nodes[index].pad = pad;
  if (count <= kLeafSize || depth >= kStack / 2 - 2) {
    for (uint32_t k = first; k < first + count; ++k) m_boxes[k] = piece_box(m_pieces[k]);
    m_nodes[index].first_or_right = first;
    m_nodes[index].count = count;
    return index;
  }
  const Vec3 ext = mid.hi - mid.lo;
  int axis = 0;
  if (ext.y() > ext[axis]) axis = 1;
  if (ext.z() > ext[axis]) axis = 2;
  const uint32_t half = count / 2;
  auto begin = m_pieces.begin() + first;
  auto key = [&](const Piece& p) {
    const MediumPlane& pl = m_planes[p.plane];
    return pl.a0[axis] + 0.5f * (p.u0 + p.u1) * pl.w0[axis] + 0.5f * (p.v0 + p.v1) * pl.w1[axis];
  };
  // Ties broken by plane and piece order: the split depends only on the (fixed) input.
  std::nth_element(begin, begin + half, begin + count, [&](const Piece& x, const Piece& y) {
    const float kx = key(x), ky = key(y);
    if (kx != ky) return kx < ky;
    if (x.plane != y.plane) return x.plane < y.plane;
    return x.u0 < y.u0 || (x.u0 == y.u0 && x.v0 < y.v0);
  });
  build_node(first, half, depth + 1);
  const uint32_t right = build_node(first + half, count - half, depth + 1);
  m_nodes[index].first_or_right = right;
  return index;
}

}  // namespace dp::integrators
