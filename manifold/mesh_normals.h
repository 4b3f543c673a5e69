// Smooth vertex normals for triangle meshes that have none, estimated with CGAL (the
// only CGAL user in Deltapath; CGAL stays inside mesh_normals.cpp). With vertex normals
// present, scene::TriangleMesh interpolates them and its surface points (and
// manifold::local_frame) carry the shading-normal derivatives dn/du, dn/dv that manifold
// walks need; a mesh without normals is flat shaded and every specular chain on it sees
// dn = 0 (faceted caustics).
//
// Called once at load time, only for meshes whose material needs it
// (needs_vertex_normals): the YAML loader calls the hook returned by
// normal_estimation_hook() when the caller passes it in scene::LoadOptions (the CLI,
// the experiment runner and bench_pt do). The Mitsuba importer keeps its own
// angle-weighted normals (Mitsuba's behaviour) and does not use the hook.
#pragma once

#include <cstddef>

#include "scene/bsdf/bsdf.h"
#include "scene/loaders/loader.h"
#include "scene/shapes/shape.h"

namespace dp::manifold {

enum class NormalMethod {
  angle_weighted,  // CGAL Polygon Mesh Processing compute_vertex_normals
  jet_fit          // CGAL jet_estimate_normals (local quadric fit over k neighbours),
                   // oriented by the angle-weighted normals; needs neighbourhoods that
                   // surround the vertex (fails at poles of lat-long spheres)
};

struct NormalEstimation {
  NormalMethod method = NormalMethod::angle_weighted;
  unsigned jet_neighbors = 12;  // k nearest welded vertices for the jet fit
};

// True if the mesh has no normals and its material has a delta or glossy lobe (a
// specular chain through it needs smooth normals and their derivatives).
bool needs_vertex_normals(const scene::TriangleMesh& mesh, const scene::Bsdf* material);

// Fills mesh.normals (one per vertex, unit, on the side of the triangle winding).
// Vertices with identical positions are welded first so split uv seams stay smooth.
// Returns the number of distinct (welded) positions. Existing normals are replaced.
size_t estimate_vertex_normals(scene::TriangleMesh& mesh, const NormalEstimation& opts = {});

// The loader hook (scene::LoadOptions::mesh_normals): if needs_vertex_normals(mesh,
// material), estimate_vertex_normals(mesh, opts) and true; otherwise false, mesh untouched.
scene::MeshNormalHook normal_estimation_hook(const NormalEstimation& opts = {});

}  // namespace dp::manifold
