// Colour-valued material parameters of the YAML format:
//   albedo: [0.8, 0.8, 0.8]            constant RGB
//   albedo: 0.5                        constant grey
//   albedo: {texture: tex/grid.png}    bitmap (8-bit PNG/JPEG decoded sRGB -> linear, or EXR)
//   albedo: {checkerboard: {color0: [..], color1: [..], scale: [su, sv]}}
//                                      scale is optional (default [1, 1]; a number = both)
#include <memory>

#include "core/error.h"
#include "scene/loaders/yaml/yaml_sections.h"

namespace dp::scene::yaml {

namespace {

void check_at_most_one(const Context& ctx, const YAML::Node& node, const std::string& name, const Rgb& c) {
  if ((c > 1.0f).any())
    value_error(ctx, node, "'" + quote_input(name) + "': reflectance components must be <= 1 (energy conservation)");
}

TexturePtr parse_bitmap(const Context& ctx, const YAML::Node& file_node, const std::string& name) {
  const std::string file = get_string(ctx, file_node, name + ".texture");
  const std::string path = resolve_path(ctx, file);
  try {
    return std::make_shared<BitmapTexture>(path);
  } catch (const Error& e) {
    throw IoError("cannot read texture '" + quote_input(file) + "': " + e.what(), ctx.file, line_of(file_node));
  }
}

TexturePtr parse_checkerboard(const Context& ctx, const YAML::Node& node, const std::string& name, bool max_one) {
  const std::string what = name + ".checkerboard";
  check_keys(ctx, node, {"color0", "color1", "scale"}, what);
  const YAML::Node n0 = require(ctx, node, "color0", what);
  const YAML::Node n1 = require(ctx, node, "color1", what);
  const Rgb c0 = get_rgb(ctx, n0, "color0");
  const Rgb c1 = get_rgb(ctx, n1, "color1");
  if (max_one) {
    check_at_most_one(ctx, n0, "color0", c0);
    check_at_most_one(ctx, n1, "color1", c1);
  }
  Vec2 scale(1, 1);
  if (const YAML::Node s = node["scale"]; s.IsDefined()) {
    scale = s.IsScalar() ? Vec2::Constant(get_float(ctx, s, "scale")) : get_vec2(ctx, s, "scale");
    if (!(scale.array() > 0.0f).all()) value_error(ctx, s, "'scale' of a checkerboard must be > 0");
  }
  return std::make_shared<CheckerboardTexture>(c0, c1, scale);
}

}  // namespace

TexturePtr parse_texture(const Context& ctx, const YAML::Node& node, const std::string& name, bool max_one) {
  if (node.IsMap()) {
    check_keys(ctx, node, {"texture", "checkerboard"}, "'" + quote_input(name) + "'");
    if (node.size() != 1)
      parse_error(ctx, node, "'" + quote_input(name) + "': give exactly one of 'texture' or 'checkerboard'");
    if (const YAML::Node f = node["texture"]; f.IsDefined()) return parse_bitmap(ctx, f, name);
    return parse_checkerboard(ctx, node["checkerboard"], name, max_one);
  }
  const Rgb c = get_rgb(ctx, node, name);
  if (max_one) check_at_most_one(ctx, node, name, c);
  return constant_texture(c);
}

}  // namespace dp::scene::yaml
