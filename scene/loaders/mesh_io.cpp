// Mesh file dispatch by extension (case-insensitive): .obj -> load_obj, .ply -> load_ply.
#include "scene/loaders/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"

namespace dp::scene {

std::unique_ptr<TriangleMesh> load_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".obj") return load_obj(path);
  if (ext == ".ply") return load_ply(path);
  throw IoError("unsupported mesh format '" + quote_input(ext) + "' (expected .obj or .ply)", path);
}

}  // namespace dp::scene
