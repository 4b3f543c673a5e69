// The `lights:` section (lights that are not shapes), a list of:
//   {type: point, position, intensity}                         intensity in W/sr
//   {type: spot, position, direction, intensity, cutoff, falloff_start}
//        cutoff: cone half-angle in degrees, 0 < cutoff <= 180 (required);
//        falloff_start: 0 <= falloff_start <= cutoff (default cutoff = hard edge)
//   {type: directional, direction, irradiance}                 direction light travels
//   {type: environment, radiance: [..]} or {type: environment, file: sky.exr}
//        constant radiance, or a lat-long map (EXR, or PNG/JPEG decoded to linear);
//        at most one environment per scene.
#include <memory>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "scene/loaders/yaml/yaml_sections.h"

namespace dp::scene::yaml {

namespace {

void warn_if_black(const Context& ctx, const YAML::Node& at, const std::string& type, const Rgb& c) {
  if (!(c > 0.0f).any()) log::warn(ctx.file, ":", line_of(at), ": ", type, " light emits nothing");
}

EmitterPtr parse_point(const Context& ctx, const YAML::Node& m) {
  check_keys(ctx, m, {"type", "position", "intensity"}, "point light");
  const Vec3 p = get_vec3(ctx, require(ctx, m, "position", "point light"), "position");
  const Rgb intensity = get_rgb(ctx, require(ctx, m, "intensity", "point light"), "intensity");
  warn_if_black(ctx, m, "point", intensity);
  return std::make_unique<PointEmitter>(p, intensity);
}

EmitterPtr parse_spot(const Context& ctx, const YAML::Node& m) {
  const std::string what = "spot light";
  check_keys(ctx, m, {"type", "position", "direction", "intensity", "cutoff", "falloff_start"}, what);
  const Vec3 p = get_vec3(ctx, require(ctx, m, "position", what), "position");
  const Vec3 d = get_direction(ctx, require(ctx, m, "direction", what), "direction");
  const Rgb intensity = get_rgb(ctx, require(ctx, m, "intensity", what), "intensity");
  const YAML::Node cn = require(ctx, m, "cutoff", what);
  const float cutoff = get_float(ctx, cn, "cutoff");
  if (!(cutoff > 0.0f && cutoff <= 180.0f)) value_error(ctx, cn, "'cutoff' must be in (0, 180] degrees");
  float falloff = cutoff;
  if (const YAML::Node fn = m["falloff_start"]; fn.IsDefined()) {
    falloff = get_float(ctx, fn, "falloff_start");
    if (!(falloff >= 0.0f && falloff <= cutoff))
      value_error(ctx, fn, "'falloff_start' must be in [0, cutoff] degrees");
  }
  warn_if_black(ctx, m, "spot", intensity);
  return std::make_unique<SpotEmitter>(p, d, intensity, cutoff, falloff);
}

EmitterPtr parse_directional(const Context& ctx, const YAML::Node& m) {
  check_keys(ctx, m, {"type", "direction", "irradiance"}, "directional light");
  const Vec3 d = get_direction(ctx, require(ctx, m, "direction", "directional light"), "direction");
  const Rgb e = get_rgb(ctx, require(ctx, m, "irradiance", "directional light"), "irradiance");
  warn_if_black(ctx, m, "directional", e);
  return std::make_unique<DirectionalEmitter>(d, e);
}

EmitterPtr parse_environment(const Context& ctx, const YAML::Node& m) {
  check_keys(ctx, m, {"type", "radiance", "file"}, "environment light");
  const YAML::Node r = m["radiance"], f = m["file"];
  if (r.IsDefined() == f.IsDefined())
    parse_error(ctx, m, "environment light needs exactly one of 'radiance' or 'file'");
  if (r.IsDefined()) return std::make_unique<EnvironmentEmitter>(get_rgb(ctx, r, "radiance"));
  const std::string file = get_string(ctx, f, "file");
  core::Image image;
  try {
    image = core::read_image(resolve_path(ctx, file));
  } catch (const Error& e) {
    throw IoError("cannot read environment map '" + quote_input(file) + "': " + e.what(), ctx.file, line_of(f));
  }
  if (image.empty()) throw IoError("environment map '" + quote_input(file) + "' is empty", ctx.file, line_of(f));
  for (const Rgb& c : image.pixels())
    if (!is_finite(c) || (c < 0.0f).any())
      value_error(ctx, f, "environment map '" + quote_input(file) + "' has negative or non-finite pixels");
  return std::make_unique<EnvironmentEmitter>(std::move(image), Mat3::Identity(), 1.0f);
}

}  // namespace

void parse_lights(LoadState& st, const YAML::Node& lights) {
  const Context& ctx = st.ctx;
  expect_sequence(ctx, lights, "lights");
  bool have_env = false;
  for (size_t i = 0; i < lights.size(); ++i) {
    const YAML::Node m = lights[i];
    const std::string what = "light " + std::to_string(i);
    expect_map(ctx, m, what);
    const YAML::Node type_node = require(ctx, m, "type", what);
    const std::string type = get_string(ctx, type_node, "type");
    EmitterPtr e;
    if (type == "point") {
      e = parse_point(ctx, m);
    } else if (type == "spot") {
      e = parse_spot(ctx, m);
    } else if (type == "directional") {
      e = parse_directional(ctx, m);
    } else if (type == "environment") {
      if (have_env) value_error(ctx, m, "a scene can have only one environment light");
      have_env = true;
      e = parse_environment(ctx, m);
    } else {
      parse_error(ctx, type_node, "unknown light type '" + quote_input(type) + "' (point, spot, directional, environment)");
    }
    st.scene.add_emitter(std::move(e));
  }
}

}  // namespace dp::scene::yaml
