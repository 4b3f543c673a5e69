#include "integrators/beam/beam_bvh.h"

#include <algorithm>
#include <cmath>

namespace dp::integrators {

double beam_segment_distance2(const Vec3& p0, const Vec3& u, double S, const Vec3& q0, const Vec3& v, double T) {
  // f(s, t) = |w0 + s u - t v|^2 with w0 = p0 - q0 is convex; its stationary point on the
  // lines solves s = b t - d, t = e + b s (b = u.v, d = u.w0, e = v.w0, |u| = |v| = 1).
  // Clamp s, take the best t for it, and if t leaves [0, T] clamp t and take the best s
  // for that t: the minimum over the rectangle lies on the edge the unconstrained optimum
  // points to (a convex quadratic's minimum over a box).
  const Eigen::Vector3d uu = u.cast<double>(), vv = v.cast<double>(), w0 = (p0 - q0).cast<double>();
  const double b = uu.dot(vv), d = uu.dot(w0), e = vv.dot(w0);
  const double denom = 1.0 - b * b;
  double s = denom > 1e-12 ? std::clamp((b * e - d) / denom, 0.0, S) : 0.0;
  double t = e + b * s;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-d, 0.0, S);
  } else if (t > T) {
    t = T;
    s = std::clamp(b * T - d, 0.0, S);
  }
  return (w0 + s * uu - t * vv).squaredNorm();
}

void BeamBvh::build(std::vector<MediumBeam> beams, float max_piece) {
  m_beams = std::move(beams);
  m_nodes.clear();
  m_pieces.clear();
  if (m_beams.empty()) return;
  const bool split = max_piece > 0.0f && std::isfinite(max_piece);
  size_t total = 0;
  for (const MediumBeam& b : m_beams) total += split ? size_t(std::ceil((b.length - b.begin) / max_piece)) : 1;
  m_pieces.reserve(total);
  for (uint32_t i = 0; i < uint32_t(m_beams.size()); ++i) {
    const float begin = m_beams[i].begin, len = m_beams[i].length;
    if (!split || !(len - begin > max_piece)) {
      m_pieces.push_back(Piece{i, begin, len});
      continue;
    }
    // [begin + k p, begin + (k + 1) p] with the last one ending at the beam's length: a
    // partition of [begin, length] (each piece's v1 is the next one's v0, computed alike).
    for (uint32_t k = 0;; ++k) {
      const float v0 = begin + float(k) * max_piece, v1 = begin + float(k + 1) * max_piece;
      if (!(v1 < len)) {
        m_pieces.push_back(Piece{i, v0, len});
        break;
      }
      m_pieces.push_back(Piece{i, v0, v1});
    }
  }
  m_nodes.reserve(2 * (m_pieces.size() / kLeafSize + 1));
  build_node(0, uint32_t(m_pieces.size()), 0);
}

void BeamBvh::release() {
  m_nodes = {};
  m_pieces = {};
  m_beams = {};
}

float BeamBvh::clip(const Vec3& o, const Vec3& d, float t_max, float r) const {
  if (m_nodes.empty()) return 0.0f;
  // 2r: a margin over the exact test.
  return grown_box_exit(m_nodes[0].lo, m_nodes[0].hi, 2.0f * r, o, d, t_max);
}

uint32_t BeamBvh::build_node(uint32_t first, uint32_t count, int depth) {
  const uint32_t index = uint32_t(m_nodes.size());
  m_nodes.emplace_back();
  Bounds3 b, mid;
  for (uint32_t k = first; k < first + count; ++k) {
    const Piece& pc = m_pieces[k];
    const Vec3 p0 = piece_point(pc, pc.v0), p1 = piece_point(pc, pc.v1);
    b.expand(p0);
    b.expand(p1);
    mid.expand(Vec3(0.5f * (p0 + p1)));
  }
  m_nodes[index].lo = b.lo;
  m_nodes[index].hi = b.hi;
  // Median splits halve the count: the depth stays below the traversal stack's bound.
  if (count <= kLeafSize || depth >= kStack / 2 - 2) {
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
  // Ties broken by beam and piece order: the split depends only on the (fixed) input.
  auto key = [&](const Piece& p) {
    const MediumBeam& bm = m_beams[p.beam];
    return bm.a[axis] + 0.5f * (p.v0 + p.v1) * bm.w[axis];
  };
  std::nth_element(begin, begin + half, begin + count, [&](const Piece& x, const Piece& y) {
    const float kx = key(x), ky = key(y);
    return kx < ky || (kx == ky && (x.beam < y.beam || (x.beam == y.beam && x.v0 < y.v0)));
  });
  build_node(first, half, depth + 1);
  const uint32_t right = build_node(first + half, count - half, depth + 1);
  m_nodes[index].first_or_right = right;
  return index;
}

}  // namespace dp::integrators
