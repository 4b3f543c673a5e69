// Triangle meshes: clean-up, area sampling and local surface geometry.
//
// Conventions (see shape.h / surface.h):
//  * Barycentrics (b1, b2) belong to vertices 1 and 2; b0 = 1 - b1 - b2.
//  * Geometric normal ng = normalize((v1 - v0) x (v2 - v0)) (the emitting side of an
//    area light; SCENE_FORMAT.md).
//  * uv: interpolated from the per-vertex uvs, or the barycentrics (b1, b2) when the
//    mesh has none, so dp/du = v1 - v0 and dp/dv = v2 - v0 in that case.
//  * Shading normal: interpolated vertex normal when `smooth` and normals exist. It is
//    deliberately NOT flipped into ng's hemisphere: a mesh whose vertex normals
//    disagree with its winding keeps them, and BSDF code decides what to do with the
//    shading/geometric mismatch (the classic pbrt-v3 flip would silently change which
//    side a shading normal belongs to).
//  * dndu/dndv are derivatives of the *normalized* interpolated normal along dp/du and
//    dp/dv (zero for flat shading).
#include <algorithm>
#include <cmath>

#include <sstream>

#include "core/error.h"
#include "core/warp.h"
#include "scene/limits.h"
#include "scene/shapes/shape.h"

namespace dp::scene {

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

// Solves [a b; c d] x = r for the pair of vectors (x0, x1) with
//   a * x0 + b * x1 = r0,  c * x0 + d * x1 = r1.
// Returns false if the system is (nearly) singular.
bool solve2(float a, float b, float c, float d, const Vec3& r0, const Vec3& r1, Vec3& x0, Vec3& x1) {
  const double det = double(a) * double(d) - double(b) * double(c);
  if (!(std::abs(det) > 1e-12) || !std::isfinite(det)) return false;
  const float inv = float(1.0 / det);
  x0 = (d * r0 - b * r1) * inv;
  x1 = (a * r1 - c * r0) * inv;
  return finite(x0) && finite(x1);
}

}  // namespace

void TriangleMesh::finalize() {
  if (!normals.empty() && normals.size() != positions.size())
    throw ValueError("mesh '" + name + "': " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(positions.size()) + " vertices");
  if (!uvs.empty() && uvs.size() != positions.size())
    throw ValueError("mesh '" + name + "': " + std::to_string(uvs.size()) + " uvs for " +
                     std::to_string(positions.size()) + " vertices");
  for (size_t i = 0; i < positions.size(); ++i)
    if (!positions[i].hasNaN() && !within_scene_limit(positions[i])) {  // NaN vertices: dropped below
      std::ostringstream os;
      os << "mesh '" << quote_input(name) << "': vertex " << i << " at (" << positions[i].x() << ", " << positions[i].y()
         << ", " << positions[i].z() << ") is beyond the scene limit (coordinates at most " << kMaxSceneMagnitudeText
         << " in magnitude, after the shape's transform)";
      throw ValueError(os.str());
    }
  std::vector<std::array<uint32_t, 3>> kept;
  kept.reserve(triangles.size());
  std::vector<double> areas;
  areas.reserve(triangles.size());
  for (const auto& tri : triangles) {
    for (uint32_t idx : tri)
      if (idx >= positions.size())
        throw ValueError("mesh '" + name + "': vertex index " + std::to_string(idx) + " out of range (" +
                         std::to_string(positions.size()) + " vertices)");
    const Vec3& v0 = positions[tri[0]];
    const Vec3& v1 = positions[tri[1]];
    const Vec3& v2 = positions[tri[2]];
    // Area in double: thin slivers whose float cross product underflows are dropped
    // only when they truly have (numerically) no area and no usable normal.
    const Vec3d e1 = (v1 - v0).cast<double>(), e2 = (v2 - v0).cast<double>();
    const double area = 0.5 * e1.cross(e2).norm();
    const Vec3 ng = (v1 - v0).cross(v2 - v0);
    const bool bad = !finite(v0) || !finite(v1) || !finite(v2) || !(area > 0.0) || !std::isfinite(area) ||
                     !(ng.squaredNorm() > 0.0f) || !finite(ng);
    if (bad) {
      ++degenerate_skipped;
      continue;
    }
    kept.push_back(tri);
    areas.push_back(area);
  }
  triangles = std::move(kept);
  double total = 0;
  for (double a : areas) total += a;
  m_cdf.resize(areas.size());
  double running = 0;
  for (size_t i = 0; i < areas.size(); ++i) {
    running += areas[i];
    m_cdf[i] = float(running / total);
  }
  if (!m_cdf.empty()) m_cdf.back() = 1.0f;
  m_cdf_lo.assign(m_cdf.size(), 0.0f);
  for (size_t i = 1; i < m_cdf.size(); ++i) m_cdf_lo[i] = m_cdf[i - 1];
  m_cdf_inv_width.assign(m_cdf.size(), 0.0f);
  for (size_t i = 0; i < m_cdf.size(); ++i) {
    const float width = m_cdf[i] - m_cdf_lo[i];
    if (width > 0.0f) m_cdf_inv_width[i] = 1.0f / width;
  }
  m_area = float(total);
  m_frames.resize(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) m_frames[i] = compute_frame(i);
}

TriangleMesh::TriangleFrame TriangleMesh::compute_frame(size_t i) const {
  const auto& tri = triangles[i];
  const Vec3& v0 = positions[tri[0]];
  const Vec3 e1 = positions[tri[1]] - v0, e2 = positions[tri[2]] - v0;
  TriangleFrame f;
  f.ng = e1.cross(e2).normalized();
  // uv parameterization and dp/du, dp/dv (pbrt-v3 Sec. 3.6.2: solve the 2x2 system
  // [du1 dv1; du2 dv2] [dpdu; dpdv] = [e1; e2]).
  Vec2 uv0(0, 0), uv1(1, 0), uv2(0, 1);
  if (!uvs.empty()) {
    uv0 = uvs[tri[0]];
    uv1 = uvs[tri[1]];
    uv2 = uvs[tri[2]];
  }
  const Vec2 duv1 = uv1 - uv0, duv2 = uv2 - uv0;
  f.uv_ok = solve2(duv1.x(), duv1.y(), duv2.x(), duv2.y(), e1, e2, f.dpdu, f.dpdv);
  if (f.uv_ok && !(f.dpdu.cross(f.dpdv).squaredNorm() > 0.0f)) f.uv_ok = false;
  if (!f.uv_ok) {
    // Degenerate uvs: an arbitrary orthonormal tangent frame around ng.
    const Frame t = Frame::from_normal(f.ng);
    f.dpdu = t.s;
    f.dpdv = t.t;
  }
  f.flat = Frame::from_normal_tangent(f.ng, f.dpdu);
  return f;
}

Bounds3 TriangleMesh::bounds() const {
  Bounds3 b;
  for (const auto& tri : triangles)
    for (uint32_t idx : tri) b.expand(positions[idx]);
  return b;
}

float TriangleMesh::triangle_area(size_t i) const {
  const auto& tri = triangles[i];
  return 0.5f * (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]).norm();
}

PositionSample TriangleMesh::sample_area(const Vec2& u) const {
  DP_CHECK(!m_cdf.empty(), "sample_area on an empty or unfinalized mesh");
  return sample_area_inline(u);
}

void TriangleMesh::fill_surface(int prim, const Vec2& b, const Ray& ray, float t, SurfacePoint& out) const {
  (void)ray;
  (void)t;
  DP_DCHECK(prim >= 0 && size_t(prim) < triangles.size(), "triangle index out of range");
  const auto& tri = triangles[size_t(prim)];
  const Vec3& v0 = positions[tri[0]];
  const Vec3& v1 = positions[tri[1]];
  const Vec3& v2 = positions[tri[2]];
  const float b1 = b.x(), b2 = b.y(), b0 = 1.0f - b1 - b2;
  const TriangleFrame& tf = m_frames[size_t(prim)];

  // Position from barycentrics (on the plane, unlike o + t d which carries the ray's
  // rounding error along d).
  out.p = b0 * v0 + b1 * v1 + b2 * v2;
  out.ng = tf.ng;
  Vec2 uv0(0, 0), uv1(1, 0), uv2(0, 1);
  if (!uvs.empty()) {
    uv0 = uvs[tri[0]];
    uv1 = uvs[tri[1]];
    uv2 = uvs[tri[2]];
  }
  out.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
  out.dpdu = tf.dpdu;
  out.dpdv = tf.dpdv;
  const bool uv_ok = tf.uv_ok;
  const Vec2 duv1 = uv1 - uv0, duv2 = uv2 - uv0;
  const Vec3 e1 = v1 - v0, e2 = v2 - v0;

  const bool shade_smooth = smooth && !normals.empty();
  out.dndu = Vec3::Zero();
  out.dndv = Vec3::Zero();
  if (!shade_smooth) {
    out.shading = tf.flat;
    return;
  }
  Vec3 ns = out.ng;
  const Vec3& n0 = normals[tri[0]];
  const Vec3& n1 = normals[tri[1]];
  const Vec3& n2 = normals[tri[2]];
  const Vec3 n_raw = b0 * n0 + b1 * n1 + b2 * n2;
  const float len = n_raw.norm();
  if (len > 0.0f && std::isfinite(len)) {
    ns = n_raw / len;
    // Derivatives of the raw interpolated normal w.r.t. the barycentrics are
    // (n1 - n0, n2 - n0). Map them to (u, v): with uvs, by the same 2x2 system as
    // dp/du; otherwise along the arbitrary tangents: find the barycentric
    // displacement (db1, db2) with e1 db1 + e2 db2 = dpdu via the Gram system.
    const Vec3 dn1 = n1 - n0, dn2 = n2 - n0;
    Vec3 dndu_raw, dndv_raw;
    bool ok;
    if (uv_ok) {
      ok = solve2(duv1.x(), duv1.y(), duv2.x(), duv2.y(), dn1, dn2, dndu_raw, dndv_raw);
    } else {
      const float g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
      const double det = double(g11) * double(g22) - double(g12) * double(g12);
      ok = std::abs(det) > 0.0;
      if (ok) {
        auto along = [&](const Vec3& tangent) {
          const double r1 = double(e1.dot(tangent)), r2 = double(e2.dot(tangent));
          const double db1 = (double(g22) * r1 - double(g12) * r2) / det;
          const double db2 = (double(g11) * r2 - double(g12) * r1) / det;
          return Vec3(dn1 * float(db1) + dn2 * float(db2));
        };
        dndu_raw = along(out.dpdu);
        dndv_raw = along(out.dpdv);
      }
    }
    if (ok) {
      // d(n/|n|) = (dn - n_hat (n_hat . dn)) / |n|
      out.dndu = (dndu_raw - ns * ns.dot(dndu_raw)) / len;
      out.dndv = (dndv_raw - ns * ns.dot(dndv_raw)) / len;
    }
  }
  out.shading = Frame::from_normal_tangent(ns, out.dpdu);
}

}  // namespace dp::scene
