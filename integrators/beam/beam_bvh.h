// Bounding volume hierarchy over one iteration's photon beams (`beam`), for the query of
// the beam-beam estimators: every beam whose segment a + v w, v in [0, length], comes
// within r of the camera segment o + t d, t in [0, t_max] (the exact segment-segment
// distance, in double: a beam farther than r cannot contribute to either kernel).
// Long beams are split into pieces [v0, v1] of at most `max_piece` (a partition of
// [begin, length], the beam's kept part, photon_tracer.h): a wall-to-wall beam in thin smoke has an AABB spanning the room, which
// every camera ray would hit; a piece's box is at most max_piece + 2r wide. The query
// reports pieces (each within r of the segment), and the estimators integrate each
// piece's range (beam_gather.h), so the pieces of one beam add up to the whole beam.
// Nodes bound the pieces; the query grows them by r, so one BVH serves any radius. Built
// by median splits of the pieces' midpoints on the widest axis down to leaves of at most
// kLeafSize pieces (deterministic for a given beam order; ties by beam and piece order).
// Queries visit the left child first with a fixed-size stack: a fixed report order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "integrators/media_photons/photon_bvh.h"  // grown_box_slab_hit
#include "integrators/media_photons/photon_tracer.h"

namespace dp::integrators {

// Squared distance between the segments p0 + s u, s in [0, S] and q0 + t v, t in [0, T]
// (u, v unit; S, T finite >= 0): the minimum of the convex quadratic over the rectangle.
double beam_segment_distance2(const Vec3& p0, const Vec3& u, double S, const Vec3& q0, const Vec3& v, double T);

class BeamBvh {
 public:
  static constexpr uint32_t kLeafSize = 16;  // per-piece box tests in a leaf; fewer nodes (measured)
  // One piece of a beam: the points a + v w, v in [v0, v1].
  struct Piece {
    uint32_t beam = 0;  // index into beams()
    float v0 = 0, v1 = 0;
  };
  // max_piece <= 0 or +inf: no split.
  void build(std::vector<MediumBeam> beams, float max_piece = 0.0f);
  void release();
  bool empty() const { return m_beams.empty(); }
  size_t size() const { return m_beams.size(); }
  size_t pieces() const { return m_pieces.size(); }
  const std::vector<MediumBeam>& beams() const { return m_beams; }

  // The parameter where the ray o + t d leaves the beams' bounds grown by 2r (min with
  // t_max); 0 if it misses them. Clips an unbounded camera segment: no beam lies beyond.
  float clip(const Vec3& o, const Vec3& d, float t_max, float r) const;

  // fn(beam, v0, v1) for every piece within r of the segment o + t d (d unit), t in
  // [0, t_max] (t_max may be +inf). `pad` false is BeamFault::bvh_unpadded: the boxes are
  // tested without r (a planted defect: pieces near a box's face are missed).
  template <class Fn>
  void query_segment(const Vec3& o, const Vec3& d, float t_max, float r, Fn&& fn, bool pad = true) const {
    if (m_nodes.empty()) return;
    const float tm = clip(o, d, t_max, r);
    if (!(tm > 0.0f)) return;
    // Float slabs with a relative margin: never tighter than the exact double test below.
    const float grow = pad ? r * 1.0001f + 1e-6f : 0.0f;
    const double r2 = double(r) * double(r);
    const Vec3 inv(1.0f / d.x(), 1.0f / d.y(), 1.0f / d.z());
    uint32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = m_nodes[stack[--top]];
      if (!slab_hit(n.lo, n.hi, o, inv, tm, grow)) continue;
      if (n.count > 0) {
        for (uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
          const Piece& pc = m_pieces[k];
          const MediumBeam& b = m_beams[pc.beam];
          const Vec3 p0 = b.a + pc.v0 * b.w, p1 = b.a + pc.v1 * b.w;
          if (!slab_hit(p0.cwiseMin(p1), p0.cwiseMax(p1), o, inv, tm, grow)) continue;
          if (beam_segment_distance2(o, d, double(tm), p0, b.w, double(pc.v1 - pc.v0)) <= r2) fn(b, pc.v0, pc.v1);
        }
        continue;
      }
      stack[top++] = n.first_or_right;
      stack[top++] = uint32_t(&n - m_nodes.data()) + 1;  // the left child
    }
  }

 private:
  static constexpr int kStack = 96;
  // 32 bytes, two to a cache line (the query is bound by node and piece loads).
  struct Node {
    Vec3 lo{0, 0, 0}, hi{0, 0, 0};
    uint32_t first_or_right = 0;  // leaf: pieces [first, first + count); inner: the right child
    uint32_t count = 0;           // 0: inner node, the left child is the next node
  };
  static bool slab_hit(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inv, float t_max, float r) {
    return grown_box_slab_hit(lo, hi, o, inv, t_max, r);
  }
  Vec3 piece_point(const Piece& p, float v) const { return m_beams[p.beam].a + v * m_beams[p.beam].w; }
  uint32_t build_node(uint32_t first, uint32_t count, int depth);

  static_assert(sizeof(Node) == 32);
  std::vector<Node> m_nodes;
  std::vector<Piece> m_pieces;
  std::vector<MediumBeam> m_beams;
};

}  // namespace dp::integrators
