// The sections of a version-1 YAML scene (SCENE_FORMAT.md), one parser per concept:
// yaml_loader.cpp (document, version, camera, integrator, top-level medium),
// yaml_materials.cpp + yaml_textures.cpp, yaml_media.cpp, yaml_shapes.cpp +
// yaml_transform.cpp, yaml_lights.cpp. Internal to the YAML front end.
//
// Materials and media are parsed and validated up front (so errors in unused ones are
// still reported) and added to the Scene on first reference, so an unused glass
// material does not switch on Caps::has_specular.
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>

#include "core/math.h"
#include "scene/bsdf/bsdf.h"
#include "scene/loaders/loader.h"
#include "scene/media/medium.h"
#include "scene/scene.h"
#include "scene/bsdf/texture.h"
#include "scene/loaders/yaml/yaml_values.h"

namespace dp::scene::yaml {

struct LoadState {
  Context ctx;
  Scene& scene;

  struct MaterialDef {
    BsdfPtr bsdf;
    int index = -1;  // in Scene::bsdfs(), -1 until first use
  };
  struct MediumDef {
    HomogeneousMedium medium;
    int index = -1;  // in Scene::media(), -1 until first use
  };
  std::map<std::string, MaterialDef> materials;
  std::map<std::string, MediumDef> media;
  const LoadOptions* options = nullptr;  // owned by the caller of load_scene_yaml*
  int null_material = -1;  // `material: none` (index-matched boundary), added on first use

  // Resolve a name (a scalar node) to a scene index; ParseError for undefined names.
  int material_index(const YAML::Node& ref);
  int medium_index(const YAML::Node& ref);
};

void parse_materials(LoadState& st, const YAML::Node& materials);
void parse_media(LoadState& st, const YAML::Node& media);
void parse_shapes(LoadState& st, const YAML::Node& shapes);
void parse_lights(LoadState& st, const YAML::Node& lights);

// A colour-valued material parameter: [r, g, b], a number, {texture: file} or
// {checkerboard: {color0, color1, scale}}. If `max_one`, constant colours and
// checkerboard colours must be <= 1 (energy conservation of reflectances).
TexturePtr parse_texture(const Context& ctx, const YAML::Node& node, const std::string& name, bool max_one);

}  // namespace dp::scene::yaml
