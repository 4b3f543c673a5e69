// Mesh files: Wavefront OBJ (tinyobjloader; all groups merged, polygons triangulated)
// and PLY (ascii and binary little/big endian; vertex x y z, optional nx ny nz, u v /
// s t / texture_u texture_v, faces as vertex_indices / vertex_index lists, polygons
// fan-triangulated). Errors throw dp::IoError / dp::ParseError naming the file (and
// line for ascii formats). Degenerate triangles are removed by TriangleMesh::finalize().
#pragma once

#include <memory>
#include <string>

#include "scene/shapes/shape.h"

namespace dp::scene {

std::unique_ptr<TriangleMesh> load_mesh(const std::string& path);
std::unique_ptr<TriangleMesh> load_obj(const std::string& path);
std::unique_ptr<TriangleMesh> load_ply(const std::string& path);

}  // namespace dp::scene
