// Bounding volume hierarchy over one iteration's photon planes (`plane`; photon_plane.h):
// for a camera segment o + w d, w in [0, w_max], every plane piece whose box the segment
// passes through. A plane is the parallelogram a0 + t0 w0 + t1 w1, t0 in [t0_begin,
// t0_end], t1 in [0, t1_end]; a large one (thin smoke: wall to wall) would have a box
// spanning the room, so planes are cut into at most kMaxSplit x kMaxSplit pieces of side
// >= `max_piece` (a grid over (t0, t1), a partition of the plane; each piece's box is that
// of its four corners). A segment meets a plane in at most one point (plane_gather.h), so
// the gather accepts an intersection only from the piece whose half-open ranges hold it
// (the last piece of each range closed): every intersection is counted exactly once.
// Built by median splits of the pieces' centres on the widest axis (deterministic; ties by
// plane and piece order); queried with a fixed-size stack, left child first.
#pragma once

#include <cstdint>
#include <vector>

#include "integrators/media_photons/photon_bvh.h"  // grown_box_slab_hit
#include "integrators/media_photons/photon_plane.h"

namespace dp::integrators {

class PlaneBvh {
 public:
  static constexpr uint32_t kLeafSize = 8;
  static constexpr int kMaxSplit = 8;  // pieces per plane per parameter, at most
  struct Piece {
    uint32_t plane = 0;
    float u0 = 0, u1 = 0;  // t0 range
    float v0 = 0, v1 = 0;  // t1 range
  };
  // max_piece <= 0 or +inf: no split.
  void build(std::vector<MediumPlane> planes, float max_piece = 0.0f);
  void release();
  bool empty() const { return m_planes.empty(); }
  size_t size() const { return m_planes.size(); }
  size_t pieces() const { return m_pieces.size(); }
  const std::vector<MediumPlane>& planes() const { return m_planes; }
  // Where o + w d leaves the planes' bounds (min with w_max); 0 if it misses them.
  float clip(const Vec3& o, const Vec3& d, float w_max) const;

  // fn(plane, piece) for every piece whose box the segment o + w d, w in [0, w_max]
  // (d unit; w_max may be +inf) passes through.
  template <class Fn>
  void query_segment(const Vec3& o, const Vec3& d, float w_max, Fn&& fn) const {
    if (m_nodes.empty()) return;
    const float wm = clip(o, d, w_max);
    if (!(wm > 0.0f)) return;
    const Vec3 inv(1.0f / d.x(), 1.0f / d.y(), 1.0f / d.z());
    uint32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = m_nodes[stack[--top]];
      if (!grown_box_slab_hit(n.lo, n.hi, o, inv, wm, n.pad)) continue;
      if (n.count > 0) {
        for (uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
          const Piece& pc = m_pieces[k];
          if (grown_box_slab_hit(m_boxes[k].lo, m_boxes[k].hi, o, inv, wm, m_boxes[k].pad)) fn(m_planes[pc.plane], pc);
        }
        continue;
      }
      stack[top++] = n.first_or_right;
      stack[top++] = uint32_t(&n - m_nodes.data()) + 1;
    }
  }

 private:
  static constexpr int kStack = 96;
  struct Box {
    Vec3 lo{0, 0, 0}, hi{0, 0, 0};
    float pad = 0;  // a relative margin: the float box never tighter than the double intersection
  };
  struct Node {
    Vec3 lo{0, 0, 0}, hi{0, 0, 0};
    float pad = 0;
    uint32_t first_or_right = 0;  // leaf: pieces [first, first + count); inner: the right child
    uint32_t count = 0;           // 0: inner node, the left child is the next node
  };
  Box piece_box(const Piece& p) const;
  uint32_t build_node(uint32_t first, uint32_t count, int depth);

  std::vector<Node> m_nodes;
  std::vector<Piece> m_pieces;
  std::vector<Box> m_boxes;  // parallel to m_pieces
  std::vector<MediumPlane> m_planes;
};

}  // namespace dp::integrators
