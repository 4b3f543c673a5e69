// Scene front ends. load_scene dispatches on the extension: .yaml/.yml -> the YAML
// format of SCENE_FORMAT.md, .xml -> the Mitsuba importer (when available). Errors a
// user can cause throw dp::Error subclasses whose what() is one line "file:line: problem".
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "scene/bsdf/bsdf.h"
#include "scene/scene.h"
#include "scene/shapes/shape.h"

namespace dp::scene {

// Called by the YAML loader once per `type: mesh` shape with `smooth: true` whose file
// has no vertex normals, after its transform and clean-up and before it is added to the
// scene, with the shape's material (nullptr if none). Returns true if it filled
// mesh.normals (one unit normal per vertex); the loader then re-finalizes the mesh and
// logs one info line. Upper layers supply it (manifold::normal_estimation_hook()); the
// scene layer itself never estimates normals.
using MeshNormalHook = std::function<bool(TriangleMesh& mesh, const Bsdf* material)>;

struct LoadOptions {
  MeshNormalHook mesh_normals;  // empty: meshes without normals stay flat shaded
};

// Options apply to the YAML front end; the Mitsuba importer ignores them (it computes
// its own angle-weighted normals where Mitsuba does).
std::unique_ptr<Scene> load_scene(const std::string& path, const LoadOptions& options = {});
std::unique_ptr<Scene> load_scene_yaml(const std::string& path, const LoadOptions& options = {});
// Parses YAML text as if read from `path` (used by tests; relative file references
// resolve against path's folder).
std::unique_ptr<Scene> load_scene_yaml_string(const std::string& text, const std::string& path,
                                              const LoadOptions& options = {});

}  // namespace dp::scene
