// Local differential geometry in double for manifold walks, and ray re-tracing that
// refines Embree's float hit in double.
//
// Meshes: the point is projected onto the plane of its triangle; barycentrics, dp/du,
// dp/dv, the interpolated shading normal and its derivatives follow the conventions of
// scene/shapes/triangle_mesh.cpp (uv = barycentrics (b1, b2) when the mesh has no uvs).
// dn/du of a mesh comes from interpolated vertex normals; a mesh without normals is flat
// shaded (dn = 0) unless estimate_vertex_normals() (mesh_normals.h) filled them.
// Spheres: the point is projected onto the sphere; T1 along dp/du = 2 pi (-y, x, 0) (the
// scene's sphere parameterization), which degenerates at the poles (returns false).
#pragma once

#include <optional>

#include "manifold/chain.h"
#include "scene/scene.h"

namespace dp::manifold {

// Fills `out` for the point nearest to p on primitive `prim` of `shape`. False if the
// local frame is degenerate (zero-area triangle, sphere pole, zero shading normal).
bool local_frame(const scene::Shape& shape, int prim, const Vec3d& p, LocalFrame& out);

// Computes the constraint frame (s, t) and its derivatives from n, T1, dn*, dT1_*.
// False if T1 is (nearly) parallel to the shading normal.
bool finish_frame(LocalFrame& f);

// A chain vertex at a scene hit, local geometry recomputed in double.
std::optional<ChainVertex> make_vertex(const scene::Scene& scene, const scene::SurfaceHit& hit, Interaction type,
                                       double eta = 1.0);
// A chain vertex from float surface data only (no shape to refine against).
ChainVertex make_vertex(const scene::SurfacePoint& sp, Interaction type, double eta = 1.0);
// A pinned start without a surface (point light, pinhole camera).
ChainVertex make_point(const Vec3d& p);
// The end of a chain that ends in a medium (Chain::end_plane): the virtual plane through p
// with unit normal `normal` (flat: no normal derivatives; any orthonormal tangents).
ChainVertex make_plane_end(const Vec3d& p, const Vec3d& normal);

struct TraceHit {
  int32_t shape = -1, prim = -1;
  Vec3d p{0, 0, 0};
  double t = 0;
};

// Nearest hit of the ray (origin, unit dir), found by Embree in float and refined in
// double on the hit primitive. `ng_origin` (may be zero) offsets the float origin to the
// side of `dir` to avoid self-intersection.
std::optional<TraceHit> trace(const scene::Scene& scene, const Vec3d& origin, const Vec3d& dir,
                              const Vec3d& ng_origin);

}  // namespace dp::manifold
