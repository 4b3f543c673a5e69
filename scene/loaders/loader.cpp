// Front-end dispatch by file extension (case-insensitive): .yaml/.yml -> YAML format
// (SCENE_FORMAT.md), .xml -> Mitsuba importer (mitsuba_loader.h).
#include "scene/loaders/loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"

namespace dp::scene {

std::unique_ptr<Scene> load_scene(const std::string& path, const LoadOptions& options) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".yaml" || ext == ".yml") return load_scene_yaml(path, options);
  if (ext == ".xml") return load_scene_mitsuba(path);
  throw IoError("unknown scene file type '" + quote_input(ext) + "' (expected .yaml, .yml or .xml)", path);
}

}  // namespace dp::scene
