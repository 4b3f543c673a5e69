// Mitsuba's ".serialized" triangle-mesh format (Mitsuba 0.4+ versions 3 and 4): per
// mesh a little-endian header (uint16 0x041C, uint16 version), then a zlib stream
// holding flags, (v4) a name, vertex/triangle counts, positions, optional normals,
// texture coordinates and colours (float or double), and uint32 triangle indices.
// Several meshes may be concatenated; the file ends with their byte offsets (uint32 in
// v3, uint64 in v4) and a uint32 mesh count. Vertex colours are skipped.
#pragma once

#include <memory>
#include <string>

#include "scene/shapes/shape.h"

namespace dp::scene {

struct SerializedMesh {
  std::unique_ptr<TriangleMesh> mesh;  // not finalized; positions in object space
  bool face_normals = false;           // the file's "use face normals" flag (0x0010)
};

// Throws IoError (unreadable file) or ParseError (corrupt data, shape_index out of
// range), naming the file.
SerializedMesh load_serialized(const std::string& path, int shape_index);

}  // namespace dp::scene
