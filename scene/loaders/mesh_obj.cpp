// Wavefront OBJ via tinyobjloader: all objects/groups merged into one mesh, polygons
// triangulated, materials (.mtl) ignored. OBJ indexes positions, normals and uvs
// separately per face corner; each distinct (position, normal, uv) corner becomes one
// vertex of the output. Normals (uvs) are used only if every corner has one, otherwise
// the mesh is flat-shaded (uses barycentric uvs), as a partial set cannot be
// interpolated consistently.
#include <tiny_obj_loader.h>

#include <array>
#include <fstream>
#include <unordered_map>

#include "core/error.h"
#include "core/log.h"
#include "core/read_file.h"
#include "scene/loaders/mesh_io.h"

namespace dp::scene {

namespace {

struct CornerHash {
  size_t operator()(const std::array<int, 3>& k) const {
    size_t h = std::hash<int>()(k[0]);
    h = h * 0x9E3779B97F4A7C15ull + std::hash<int>()(k[1]);
    h = h * 0x9E3779B97F4A7C15ull + std::hash<int>()(k[2]);
    return h;
  }
};

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s;
}

}  // namespace

std::unique_ptr<TriangleMesh> load_obj(const std::string& path) {
  core::check_readable_file(path, "mesh file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    const std::string msg = trim(reader.Error());
    throw ParseError("cannot parse OBJ: " + (msg.empty() ? std::string("unknown error") : quote_input(msg, 200)), path);
  }
  if (!reader.Warning().empty()) log::debug(path, ": ", trim(reader.Warning()));

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3, nt = attrib.texcoords.size() / 2;
  bool all_normals = true, all_uvs = true;
  size_t corners = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& idx : shape.mesh.indices) {
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv)
        throw ParseError("vertex index " + std::to_string(idx.vertex_index + 1) + " out of range (" +
                             std::to_string(nv) + " vertices)", path);
      if (idx.normal_index >= 0 && size_t(idx.normal_index) >= nn)
        throw ParseError("normal index " + std::to_string(idx.normal_index + 1) + " out of range", path);
      if (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt)
        throw ParseError("texture coordinate index " + std::to_string(idx.texcoord_index + 1) + " out of range", path);
      all_normals &= idx.normal_index >= 0;
      all_uvs &= idx.texcoord_index >= 0;
      ++corners;
    }
  }
  if (corners == 0) throw ParseError("OBJ file has no faces", path);

  auto mesh = std::make_unique<TriangleMesh>();
  mesh->name = path;
  std::unordered_map<std::array<int, 3>, uint32_t, CornerHash> remap;
  remap.reserve(corners);
  auto vertex_of = [&](const tinyobj::index_t& idx) -> uint32_t {
    const std::array<int, 3> key{idx.vertex_index, all_normals ? idx.normal_index : -1,
                                 all_uvs ? idx.texcoord_index : -1};
    auto [it, inserted] = remap.try_emplace(key, uint32_t(mesh->positions.size()));
    if (inserted) {
      const size_t v = size_t(key[0]);
      mesh->positions.emplace_back(float(attrib.vertices[3 * v]), float(attrib.vertices[3 * v + 1]),
                                   float(attrib.vertices[3 * v + 2]));
      if (all_normals) {
        const size_t n = size_t(key[1]);
        mesh->normals.emplace_back(float(attrib.normals[3 * n]), float(attrib.normals[3 * n + 1]),
                                   float(attrib.normals[3 * n + 2]));
      }
      if (all_uvs) {
        const size_t t = size_t(key[2]);
        mesh->uvs.emplace_back(float(attrib.texcoords[2 * t]), float(attrib.texcoords[2 * t + 1]));
      }
    }
    return it->second;
  };

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    size_t offset = 0;
    for (const auto face_size : shape.mesh.num_face_vertices) {
      const size_t fv = size_t(face_size);
      if (offset + fv > indices.size()) throw ParseError("inconsistent face data in '" + quote_input(shape.name) + "'", path);
      // Fan triangulation covers polygons tinyobjloader left untriangulated.
      for (size_t k = 1; k + 1 < fv; ++k)
        mesh->triangles.push_back(
            {vertex_of(indices[offset]), vertex_of(indices[offset + k]), vertex_of(indices[offset + k + 1])});
      offset += fv;
    }
  }
  for (Vec3& n : mesh->normals) n.normalize();
  return mesh;
}

}  // namespace dp::scene
