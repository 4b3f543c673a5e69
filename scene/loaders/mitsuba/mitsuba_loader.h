// Mitsuba XML front end: reads Mitsuba 0.5/0.6 and Mitsuba 3 scene files into the
// one scene::Scene (the same representation the YAML loader builds). The supported
// subset, its substitutions and their consequences are listed in mitsuba_loader.cpp.
// Errors a user can cause throw dp::Error subclasses whose what() is one line
// "file:line: problem"; ignored or substituted parameters are reported as one warning
// line each (file:line: name: what was done).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace dp::scene {

struct MitsubaOptions {
  // Values for $name parameters; they take precedence over the file's <default>s.
  std::map<std::string, std::string> parameters;
  // If set, every warning line is also appended here (tests inspect them).
  std::vector<std::string>* warnings = nullptr;
};

std::unique_ptr<Scene> load_scene_mitsuba(const std::string& path);
std::unique_ptr<Scene> load_scene_mitsuba(const std::string& path, const MitsubaOptions& options);
// Parses XML text as if read from `path` (relative file references resolve against
// path's folder).
std::unique_ptr<Scene> load_scene_mitsuba_string(const std::string& xml, const std::string& path,
                                                 const MitsubaOptions& options = {});

}  // namespace dp::scene
