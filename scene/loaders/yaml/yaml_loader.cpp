// YAML scene front end (SCENE_FORMAT.md, version 1): the document, `version`, `camera`,
// `integrator` and the top-level `medium`; the other sections are parsed by
// yaml_materials/yaml_media/yaml_shapes/yaml_lights.cpp. Sections are read in
// dependency order (materials and media before shapes), whatever order the file uses.
//
// camera: type (perspective, optional), position, look_at or direction (exactly one),
//         up (default [0, 1, 0]), fov (degrees, 0 < fov < 180), fov_axis (x | y,
//         default y), resolution [width, height] — position, look_at/direction, fov and
//         resolution are required.
// integrator: type (default path), max_depth (>= 1, default 8), spp (>= 1); any other
//         key is kept verbatim in IntegratorDefaults::settings for the integrator.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "core/read_file.h"
#include "scene/loaders/loader.h"
#include "scene/loaders/yaml/yaml_sections.h"

namespace dp::scene {

namespace yaml {
namespace {

CameraDesc parse_camera(const Context& ctx, const YAML::Node& m) {
  const std::string what = "camera";
  check_keys(ctx, m, {"type", "position", "look_at", "direction", "up", "fov", "fov_axis", "resolution"}, what);
  if (const YAML::Node t = m["type"]; t.IsDefined()) {
    const std::string type = get_string(ctx, t, "type");
    if (type != "perspective") parse_error(ctx, t, "unknown camera type '" + quote_input(type) + "' (perspective)");
  }
  CameraDesc desc;
  desc.position = get_vec3(ctx, require(ctx, m, "position", what), "position");
  const YAML::Node look = m["look_at"], dir = m["direction"];
  if (look.IsDefined() && dir.IsDefined())
    parse_error(ctx, dir, "camera: give either 'look_at' or 'direction', not both");
  if (look.IsDefined()) {
    desc.look_at = get_vec3(ctx, look, "look_at");
    if (!((desc.look_at - desc.position).norm() > 0.0f))
      value_error(ctx, look, "camera 'look_at' must differ from 'position'");
  } else if (dir.IsDefined()) {
    desc.look_at = desc.position + get_direction(ctx, dir, "direction");
  } else {
    parse_error(ctx, m, "missing required key 'look_at' (or 'direction') in camera");
  }
  if (const YAML::Node up = m["up"]; up.IsDefined()) {
    desc.up = get_direction(ctx, up, "up");
    const Vec3 fwd = (desc.look_at - desc.position).normalized();
    if (!(fwd.cross(desc.up).norm() > 1e-4f)) value_error(ctx, up, "camera 'up' is parallel to the view direction");
  } else {
    const Vec3 fwd = (desc.look_at - desc.position).normalized();
    if (!(fwd.cross(desc.up).norm() > 1e-4f))
      parse_error(ctx, m, "camera looks along the default up [0, 1, 0]: give 'up'");
  }
  const YAML::Node fov = require(ctx, m, "fov", what);
  desc.fov_deg = get_float(ctx, fov, "fov");
  if (!(desc.fov_deg > 0.0f && desc.fov_deg < 180.0f)) value_error(ctx, fov, "'fov' must be in (0, 180) degrees");
  if (const YAML::Node axis = m["fov_axis"]; axis.IsDefined()) {
    const std::string a = get_string(ctx, axis, "fov_axis");
    if (a != "x" && a != "y") value_error(ctx, axis, "'fov_axis' must be x or y (got '" + quote_input(a) + "')");
    desc.fov_axis_x = a == "x";
  }
  const YAML::Node res = require(ctx, m, "resolution", what);
  if (!res.IsSequence() || res.size() != 2)
    parse_error(ctx, res, "'resolution' must be a list [width, height]");
  desc.width = get_int(ctx, res[0], "resolution");
  desc.height = get_int(ctx, res[1], "resolution");
  if (!valid_image_size(desc.width, desc.height))
    value_error(ctx, res, "'resolution' must be between 1 and 65536 pixels per side, at most 67108864 (8192 x 8192) in total");
  return desc;
}

IntegratorDefaults parse_integrator(const Context& ctx, const YAML::Node& m) {
  expect_map(ctx, m, "integrator");
  IntegratorDefaults d;
  for (auto it = m.begin(); it != m.end(); ++it) {
    const std::string key = get_string(ctx, it->first, "integrator key");
    if (key == "type") {
      d.type = get_string(ctx, it->second, "type");
    } else if (key == "max_depth") {
      d.max_depth = get_int(ctx, it->second, "max_depth");
      if (d.max_depth < 1) value_error(ctx, it->second, "'max_depth' must be >= 1");
    } else if (key == "spp") {
      d.spp = get_int(ctx, it->second, "spp");
      if (d.spp < 1) value_error(ctx, it->second, "'spp' must be >= 1");
    } else {
      if (!it->second.IsDefined() || it->second.IsNull())
        parse_error(ctx, it->first, "integrator setting '" + quote_input(key) + "' has no value");
      if (!d.settings.emplace(key, to_text(it->second)).second)
        parse_error(ctx, it->first, "duplicate key '" + quote_input(key) + "' in integrator");
    }
  }
  return d;
}

YAML::Node parse_document(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    // Errors found at the end of input (an unclosed bracket) are reported by yaml-cpp
    // on the line after the last one; point at the last line instead.
    const int last_line = int(std::count(text.begin(), text.end(), '\n')) + (text.ends_with('\n') ? 0 : 1);
    const int line = e.mark.line >= 0 ? std::min(e.mark.line + 1, std::max(last_line, 1)) : 0;
    throw ParseError("malformed YAML: " + e.msg, path, line);
  } catch (const YAML::Exception& e) {
    throw ParseError(std::string("malformed YAML: ") + e.what(), path, 0);
  }
  if (!root.IsMap()) throw ParseError("a scene file must be a YAML map with 'version: 1' at the top", path, 1);
  return root;
}

std::unique_ptr<Scene> build(const std::string& text, const std::string& path, const LoadOptions& options) {
  const YAML::Node root = parse_document(text, path);
  auto scene = std::make_unique<Scene>();
  scene->set_source(path);
  LoadState st{Context{path, std::filesystem::path(path).parent_path()}, *scene, {}, {}, &options};
  const Context& ctx = st.ctx;
  check_keys(ctx, root,
             {"version", "camera", "integrator", "materials", "media", "shapes", "lights", "medium"},
             "the scene");
  const YAML::Node version = require(ctx, root, "version", "the scene");
  if (get_int(ctx, version, "version") != 1)
    parse_error(ctx, version, "unsupported scene format version " + version.Scalar() + " (this build reads 1)");

  scene->set_camera(parse_camera(ctx, require(ctx, root, "camera", "the scene")));
  if (const YAML::Node n = root["integrator"]; n.IsDefined()) scene->set_integrator_defaults(parse_integrator(ctx, n));
  if (const YAML::Node n = root["materials"]; n.IsDefined() && !n.IsNull()) parse_materials(st, n);
  if (const YAML::Node n = root["media"]; n.IsDefined() && !n.IsNull()) parse_media(st, n);
  if (const YAML::Node n = root["shapes"]; n.IsDefined() && !n.IsNull()) parse_shapes(st, n);
  if (const YAML::Node n = root["lights"]; n.IsDefined() && !n.IsNull()) parse_lights(st, n);
  if (const YAML::Node n = root["medium"]; n.IsDefined()) scene->set_camera_medium(st.medium_index(n));
  if (scene->emitters().empty()) log::warn(path, ": the scene has no lights (it will render black)");
  try {
    scene->commit();
  } catch (const Error& e) {
    throw ValueError(e.message(), path, 0);
  }
  return scene;
}

}  // namespace
}  // namespace yaml

std::unique_ptr<Scene> load_scene_yaml_string(const std::string& text, const std::string& path,
                                              const LoadOptions& options) {
  return yaml::build(text, path, options);
}

std::unique_ptr<Scene> load_scene_yaml(const std::string& path, const LoadOptions& options) {
  return yaml::build(core::read_file(path, "scene file"), path, options);
}

}  // namespace dp::scene
