// Scene front ends. load_scene dispatches on the extension: .yaml/.yml -> the YAML
// format of SCENE_FORMAT.md, .xml -> the Mitsuba importer (when available). Errors a
// user can cause throw dp::Error subclasses whose what() is one line "file:line: problem".
#pragma once

#include <memory>
#include <string>

#include "scene/scene.h"

namespace dp::scene {

std::unique_ptr<Scene> load_scene(const std::string& path);
std::unique_ptr<Scene> load_scene_yaml(const std::string& path);
// Parses YAML text as if read from `path` (used by tests; relative file references
// resolve against path's folder).
std::unique_ptr<Scene> load_scene_yaml_string(const std::string& text, const std::string& path);

}  // namespace dp::scene
