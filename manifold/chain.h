// Specular chains for manifold walks (Jakob & Marschner 2012, "Manifold exploration",
// Sec. 4). A chain x_0 .. x_n has a pinned start x_0 (a position, or a direction for
// directional lights), interior vertices x_1 .. x_{n-1} that are specular (or glossy
// treated as specular with a prescribed half vector), and a movable end x_n on a
// surface. The chain is its own representation, independent of pathspace/: adapters
// convert paths to chains.
//
// Everything here is double precision. Local geometry of a vertex is re-evaluated in
// double from the shape's data (local_geometry.h), not copied from the float
// SurfaceHit, so constraints can be solved to 1e-7 relative and beyond.
//
// Per-vertex tangent parameterization: a vertex moves in its geometric tangent plane
// along the orthonormal tangents (T1, T2), T1 parallel to dp/du. All 2x2 derivative
// blocks, tangent maps and determinants are expressed in these coordinates (per unit
// length), and constraints in the constraint frame (s, t) below.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace dp::manifold {

using Mat2d = Eigen::Matrix2d;
using Mat3d = Eigen::Matrix3d;

enum class Interaction : uint8_t { reflection, refraction };
enum class Pin : uint8_t { position, direction };

// Local differential geometry of a surface point, in double.
struct LocalFrame {
  Vec3d p{0, 0, 0};
  Vec3d ng{0, 0, 1};              // geometric normal (unit)
  Vec3d n{0, 0, 1};               // shading normal (unit)
  Vec3d T1{1, 0, 0}, T2{0, 1, 0};  // orthonormal geometric tangents, T1 along dp/du
  Vec3d dn1{0, 0, 0}, dn2{0, 0, 0};    // d n / d(T1), d n / d(T2) (per unit length)
  Vec3d dT1_1{0, 0, 0}, dT1_2{0, 0, 0};  // d T1 / d(T1), d T1 / d(T2) (0 on meshes)
  // Constraint frame: s = normalize(T1 - n (n.T1)), t = n x s. Equal to the scene's
  // shading frame (Frame::from_normal_tangent(n, dpdu)), so projected half vectors here
  // are the local-frame coordinates the BSDFs see.
  Vec3d s{1, 0, 0}, t{0, 1, 0};
  // Derivatives of s and t along T1 and T2 (include the shading-normal derivatives).
  Vec3d ds1{0, 0, 0}, ds2{0, 0, 0}, dt1{0, 0, 0}, dt2{0, 0, 0};
};

struct ChainVertex {
  LocalFrame f;
  Interaction type = Interaction::reflection;
  double eta = 1;  // interior / exterior index of refraction (refraction only)
  // Prescribed projected half vector (microfacet normal in (s, t)); 0 = ideal specular.
  Vec2d target{0, 0};
  int32_t shape = -1, prim = -1;  // shape index (same-object checks), primitive
  bool has_surface = true;        // false for a pinned start without a surface (point light, pinhole)
  const Vec3d& p() const { return f.p; }
};

struct Chain {
  Pin pin = Pin::position;
  // Pin::direction: unit direction of propagation from the start toward x_1; v[0].p is
  // then an arbitrary point on the incoming ray (used only to re-trace from outside).
  Vec3d start_dir{0, 0, -1};
  std::vector<ChainVertex> v;  // v[0] = x_0, v[1..n-1] specular, v[n] = movable end
  // The end is a point in a medium, not on a surface (a volume photon; Gruson et al. 2018,
  // Sec. 4.3): v[n] lies on a virtual plane (v[n].f: its point, normal and tangents, no
  // curvature; local_geometry.h's make_plane_end) that re-traces intersect analytically
  // instead of the scene. Occlusion of the last segment is the caller's.
  bool end_plane = false;
  int n() const { return int(v.size()) - 1; }
  bool valid_shape() const { return v.size() >= 3; }
};

enum class WalkStatus : uint8_t {
  ok,
  singular,          // a 2x2 block (or its Schur complement) is singular: non-manifold
  total_internal_reflection,
  grazing,           // half vector / ray tangent to a surface, or a side flip
  miss,              // a re-traced ray left the scene
  different_object,  // a re-traced ray hit another shape than the chain vertex
  index_matched,     // refraction with eta = 1 (normalized half vector undefined)
  max_iterations,    // iteration limit reached without convergence
  step_too_small,    // step halving reached the floor: the distance kept growing
  not_reversible,    // walking back did not recover the start
  invalid_input      // non-finite or degenerate input chain
};
constexpr int kWalkStatusCount = 11;
const char* to_string(WalkStatus s);

}  // namespace dp::manifold
