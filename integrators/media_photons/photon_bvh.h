// Bounding volume hierarchy over one iteration's medium photons, for the two queries of
// the volumetric density estimators:
//  * point query (`vpm`): every photon within r of a point;
//  * beam query (`bre`; Jarosz et al. 2008, Sec. 4): every photon within r of a ray
//    segment o + t d, t in [0, t_max], whose projection onto the ray falls in the
//    segment (reported with that t and the squared perpendicular distance).
// Built by median splits on the widest axis down to leaves of at most kLeafSize photons
// (deterministic for a given photon order); photons are kept in leaf order. Queries visit
// children near-first with a fixed-size stack and report photons in a fixed order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "integrators/media_photons/photon_tracer.h"

namespace dp::integrators {

// The ray o + t d (inv = 1 / d per axis) has parameters in [0, t_max] inside the box
// [lo - r, hi + r] (the photon and beam BVHs' traversal test).
inline bool grown_box_slab_hit(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inv, float t_max, float r) {
  float t0 = 0.0f, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    float ta = (lo[a] - r - o[a]) * inv[a], tb = (hi[a] + r - o[a]) * inv[a];
    if (ta > tb) std::swap(ta, tb);
    if (!(ta == ta)) ta = -kInfinity;  // 0 * inf: the ray lies in the slab's plane
    if (!(tb == tb)) tb = kInfinity;
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// Where the ray o + t d (d unit) leaves the box [lo - margin, hi + margin], at most t_max;
// 0 if it misses the box within [0, t_max]. The beam and plane BVHs clip an unbounded
// camera segment with it (nothing lies beyond their root's grown box).
inline float grown_box_exit(const Vec3& lo, const Vec3& hi, float margin, const Vec3& o, const Vec3& d, float t_max) {
  float t0 = 0.0f, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const float l = lo[a] - margin, h = hi[a] + margin;
    if (d[a] == 0.0f) {
      if (o[a] < l || o[a] > h) return 0.0f;
      continue;
    }
    float ta = (l - o[a]) / d[a], tb = (h - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t1 : 0.0f;
}

class PhotonBvh {
 public:
  static constexpr uint32_t kLeafSize = 8;
  void build(std::vector<MediumPhoton> photons);
  void release();
  bool empty() const { return m_photons.empty(); }
  size_t size() const { return m_photons.size(); }
  const std::vector<MediumPhoton>& photons() const { return m_photons; }

  // fn(photon, squared distance) for every photon with |p - q| <= r.
  template <class Fn>
  void query_point(const Vec3& q, float r, Fn&& fn) const {
    if (m_nodes.empty()) return;
    const float r2 = r * r;
    uint32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = m_nodes[stack[--top]];
      const Vec3 e = (n.lo - q).cwiseMax(q - n.hi).cwiseMax(Vec3::Zero());
      if (e.squaredNorm() > r2) continue;
      if (n.count > 0) {
        for (uint32_t k = n.first; k < n.first + n.count; ++k) {
          const float d2 = (m_photons[k].p - q).squaredNorm();
          if (d2 <= r2) fn(m_photons[k], d2);
        }
        continue;
      }
      stack[top++] = n.right;
      stack[top++] = uint32_t(&n - m_nodes.data()) + 1;  // the left child
    }
  }

  // fn(photon, t, squared perpendicular distance) for every photon within r of the ray
  // o + t d (d unit) with its projection t in [0, t_max] (t_max may be +inf).
  template <class Fn>
  void query_beam(const Vec3& o, const Vec3& d, float t_max, float r, Fn&& fn) const {
    if (m_nodes.empty()) return;
    const float r2 = r * r;
    const Vec3 inv(1.0f / d.x(), 1.0f / d.y(), 1.0f / d.z());
    uint32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = m_nodes[stack[--top]];
      if (!slab_hit(n, o, inv, t_max, r)) continue;
      if (n.count > 0) {
        for (uint32_t k = n.first; k < n.first + n.count; ++k) {
          const Vec3 v = m_photons[k].p - o;
          const float t = v.dot(d);
          if (!(t >= 0.0f && t <= t_max)) continue;
          const float d2 = std::max(0.0f, v.squaredNorm() - t * t);
          if (d2 <= r2) fn(m_photons[k], t, d2);
        }
        continue;
      }
      stack[top++] = n.right;
      stack[top++] = uint32_t(&n - m_nodes.data()) + 1;  // the left child
    }
  }

 private:
  static constexpr int kStack = 96;
  struct Node {
    Vec3 lo{0, 0, 0}, hi{0, 0, 0};
    uint32_t first = 0, count = 0;  // leaf: photons [first, first + count)
    uint32_t right = 0;             // inner (count 0): the left child is the next node
  };
  static bool slab_hit(const Node& n, const Vec3& o, const Vec3& inv, float t_max, float r) {
    return grown_box_slab_hit(n.lo, n.hi, o, inv, t_max, r);
  }
  uint32_t build_node(uint32_t first, uint32_t count, int depth);

  std::vector<Node> m_nodes;
  std::vector<MediumPhoton> m_photons;
};

}  // namespace dp::integrators
