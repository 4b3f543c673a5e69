// The `media:` section: name -> {type: homogeneous, sigma_a, sigma_s, phase}
//                             or {type: grid, file, sigma_t, albedo, phase}.
//   sigma_a, sigma_s: RGB or number, >= 0, per unit length (both required)
//   grid: a heterogeneous medium, sigma_t(x) = density(x) x sigma_t with the density from
//         a Mitsuba `.vol` file (scene/media/density_grid.h: its box in world units, 0
//         outside), resolved against the scene's folder; sigma_t a number > 0 (grey:
//         delta/ratio tracking need one majorant), albedo RGB or number in [0, 1]
//         (default 1); rendered by `volpath`/`path` only.
//   phase: {type: isotropic} (also spelled iso; the default when absent) or
//          {type: hg, g: ...} with -1 < g < 1 (Henyey-Greenstein, g default 0)
#include <cmath>

#include <memory>

#include "core/error.h"
#include "scene/loaders/yaml/yaml_sections.h"

namespace dp::scene::yaml {

namespace {

PhaseFunctionDesc parse_phase(const Context& ctx, const YAML::Node& p) {
  PhaseFunctionDesc desc;
  expect_map(ctx, p, "phase");
  const YAML::Node type_node = require(ctx, p, "type", "phase");
  const std::string type = get_string(ctx, type_node, "type");
  if (type == "isotropic" || type == "iso") {
    check_keys(ctx, p, {"type"}, "isotropic phase function");
    desc.type = PhaseFunctionDesc::Type::isotropic;
  } else if (type == "hg") {
    check_keys(ctx, p, {"type", "g"}, "hg phase function");
    desc.type = PhaseFunctionDesc::Type::hg;
    if (const YAML::Node g = p["g"]; g.IsDefined()) {
      desc.g = get_float(ctx, g, "g");
      if (!(std::abs(desc.g) < 1.0f)) value_error(ctx, g, "'g' must satisfy -1 < g < 1");
    }
  } else {
    parse_error(ctx, type_node, "unknown phase function type '" + quote_input(type) + "' (isotropic, hg)");
  }
  return desc;
}

HomogeneousMedium parse_grid_medium(const Context& ctx, const std::string& name, const YAML::Node& m,
                                    const std::string& what) {
  check_keys(ctx, m, {"type", "file", "sigma_t", "albedo", "phase"}, what);
  HomogeneousMedium med;
  med.name = name;
  const YAML::Node file_node = require(ctx, m, "file", what);
  const std::string file = get_string(ctx, file_node, "file");
  try {
    med.density = std::make_shared<const DensityGrid>(read_vol_file(resolve_path(ctx, file)));
  } catch (const IoError& e) {
    throw IoError("cannot load density grid '" + quote_input(file) + "': " + e.message(), ctx.file, line_of(file_node));
  } catch (const Error& e) {
    throw ParseError("invalid density grid '" + quote_input(file) + "': " + e.message(), ctx.file, line_of(file_node));
  }
  const YAML::Node st_node = require(ctx, m, "sigma_t", what);
  const float st = get_float(ctx, st_node, "sigma_t");
  check_positive(ctx, st_node, "sigma_t", st);
  Rgb albedo = Rgb::Ones();
  if (const YAML::Node a = m["albedo"]; a.IsDefined()) {
    albedo = get_rgb(ctx, a, "albedo");
    if (!(albedo >= 0.0f).all() || !(albedo <= 1.0f).all()) value_error(ctx, a, "'albedo' must be in [0, 1]");
  }
  med.sigma_s = st * albedo;
  med.sigma_a = Rgb::Constant(st) - med.sigma_s;
  if (const YAML::Node p = m["phase"]; p.IsDefined()) med.phase = parse_phase(ctx, p);
  return med;
}

HomogeneousMedium parse_medium(const Context& ctx, const std::string& name, const YAML::Node& m) {
  const std::string what = "medium '" + quote_input(name) + "'";
  expect_map(ctx, m, what);
  const YAML::Node type_node = require(ctx, m, "type", what);
  const std::string type = get_string(ctx, type_node, "type");
  if (type == "grid") return parse_grid_medium(ctx, name, m, what);
  if (type != "homogeneous") parse_error(ctx, type_node, "unknown medium type '" + quote_input(type) + "' (homogeneous, grid)");
  check_keys(ctx, m, {"type", "sigma_a", "sigma_s", "phase"}, what);
  HomogeneousMedium med;
  med.name = name;
  med.sigma_a = get_rgb(ctx, require(ctx, m, "sigma_a", what), "sigma_a");
  med.sigma_s = get_rgb(ctx, require(ctx, m, "sigma_s", what), "sigma_s");
  if (const YAML::Node p = m["phase"]; p.IsDefined()) med.phase = parse_phase(ctx, p);
  return med;
}

}  // namespace

void parse_media(LoadState& st, const YAML::Node& media) {
  expect_map(st.ctx, media, "media");
  for (auto it = media.begin(); it != media.end(); ++it) {
    const std::string name = get_string(st.ctx, it->first, "medium name");
    if (st.media.count(name)) parse_error(st.ctx, it->first, "medium '" + quote_input(name) + "' is defined twice");
    st.media[name].medium = parse_medium(st.ctx, name, it->second);
  }
}

int LoadState::medium_index(const YAML::Node& ref) {
  const std::string name = get_string(ctx, ref, "medium");
  auto it = media.find(name);
  if (it == media.end()) parse_error(ctx, ref, "undefined medium '" + quote_input(name) + "'");
  if (it->second.index < 0) it->second.index = scene.add_medium(it->second.medium);
  return it->second.index;
}

}  // namespace dp::scene::yaml
