// The `media:` section: name -> {type: homogeneous, sigma_a, sigma_s, phase}.
//   sigma_a, sigma_s: RGB or number, >= 0, per unit length (both required)
//   phase: {type: isotropic} (also spelled iso; the default when absent) or
//          {type: hg, g: ...} with -1 < g < 1 (Henyey-Greenstein, g default 0)
#include <cmath>

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

HomogeneousMedium parse_medium(const Context& ctx, const std::string& name, const YAML::Node& m) {
  const std::string what = "medium '" + quote_input(name) + "'";
  expect_map(ctx, m, what);
  const YAML::Node type_node = require(ctx, m, "type", what);
  const std::string type = get_string(ctx, type_node, "type");
  if (type != "homogeneous") parse_error(ctx, type_node, "unknown medium type '" + quote_input(type) + "' (homogeneous)");
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
