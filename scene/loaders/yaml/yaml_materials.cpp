// The `materials:` section: a map name -> {type: ..., parameters}. Keys per type, with
// defaults for the optional ones (roughness is the microfacet alpha; 0 = ideal
// specular; distribution is beckmann | ggx, default ggx):
//   diffuse:    albedo (required)
//   phong:      diffuse, specular, exponent (all required; diffuse + specular <= 1)
//   mirror:     reflectance (default 1)
//   dielectric: ior (required), ext_ior (1), roughness (0), distribution
//   conductor:  reflectance (Schlick F0) or both eta and k (complex IOR per channel),
//               roughness (0), distribution
//   plastic:    diffuse (required), ior (1.5), ext_ior (1), roughness (0), distribution
// Opaque materials (all but dielectric) are wrapped with make_two_sided so they reflect
// on both sides; a dielectric is an interface whose two sides differ.
#include <cmath>

#include "core/error.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/loaders/yaml/yaml_sections.h"

namespace dp::scene::yaml {

namespace {

MicrofacetType parse_distribution(const Context& ctx, const YAML::Node& m) {
  const YAML::Node d = m["distribution"];
  if (!d.IsDefined()) return MicrofacetType::ggx;
  const std::string s = get_string(ctx, d, "distribution");
  if (s == "ggx") return MicrofacetType::ggx;
  if (s == "beckmann") return MicrofacetType::beckmann;
  value_error(ctx, d, "'distribution' must be beckmann or ggx (got '" + quote_input(s) + "')");
}

float parse_roughness(const Context& ctx, const YAML::Node& m) {
  const YAML::Node r = m["roughness"];
  if (!r.IsDefined()) return 0.0f;
  const float v = get_float(ctx, r, "roughness");
  check_nonnegative(ctx, r, "roughness", v);
  return v;
}

float parse_ior(const Context& ctx, const YAML::Node& m, const std::string& key, float fallback, bool required,
                const std::string& what) {
  const YAML::Node n = required ? require(ctx, m, key, what) : m[key];
  if (!n.IsDefined()) return fallback;
  const float v = get_float(ctx, n, key);
  check_positive(ctx, n, key, v);
  return v;
}

// The constant value of a texture parameter, if it is one (for cross-parameter checks).
bool constant_value(const TexturePtr& t, Rgb& out) {
  if (!t->is_constant()) return false;
  out = t->mean();
  return true;
}

BsdfPtr parse_diffuse(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "albedo"}, what);
  return make_two_sided(make_diffuse(parse_texture(ctx, require(ctx, m, "albedo", what), "albedo", true)));
}

BsdfPtr parse_phong(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "diffuse", "specular", "exponent"}, what);
  TexturePtr kd = parse_texture(ctx, require(ctx, m, "diffuse", what), "diffuse", true);
  TexturePtr ks = parse_texture(ctx, require(ctx, m, "specular", what), "specular", true);
  const YAML::Node en = require(ctx, m, "exponent", what);
  const float exponent = get_float(ctx, en, "exponent");
  check_nonnegative(ctx, en, "exponent", exponent);
  Rgb cd, cs;
  if (constant_value(kd, cd) && constant_value(ks, cs) && ((cd + cs) > 1.0f + 1e-6f).any())
    value_error(ctx, m, "phong: diffuse + specular must be <= 1 per channel (energy conservation)");
  return make_two_sided(make_phong(std::move(kd), std::move(ks), exponent));
}

BsdfPtr parse_mirror(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "reflectance"}, what);
  const YAML::Node r = m["reflectance"];
  TexturePtr refl = r.IsDefined() ? parse_texture(ctx, r, "reflectance", true) : constant_texture(Rgb::Ones());
  return make_two_sided(make_mirror(std::move(refl)));
}

BsdfPtr parse_dielectric(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "ior", "ext_ior", "roughness", "distribution"}, what);
  const float ior = parse_ior(ctx, m, "ior", 1.5f, true, what);
  const float ext_ior = parse_ior(ctx, m, "ext_ior", 1.0f, false, what);
  return make_dielectric(ior, ext_ior, parse_roughness(ctx, m), parse_distribution(ctx, m));
}

BsdfPtr parse_conductor(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "reflectance", "eta", "k", "roughness", "distribution"}, what);
  ConductorFresnel fresnel;
  const YAML::Node refl = m["reflectance"], eta = m["eta"], k = m["k"];
  if (refl.IsDefined()) {
    if (eta.IsDefined() || k.IsDefined())
      parse_error(ctx, refl, "conductor: give either 'reflectance' or 'eta' and 'k', not both");
    fresnel.kind = ConductorFresnel::Kind::schlick;
    fresnel.f0 = get_rgb(ctx, refl, "reflectance");
    if ((fresnel.f0 > 1.0f).any()) value_error(ctx, refl, "'reflectance' components must be <= 1");
  } else if (eta.IsDefined() || k.IsDefined()) {
    fresnel.kind = ConductorFresnel::Kind::complex;
    const YAML::Node en = require(ctx, m, "eta", what);
    const YAML::Node kn = require(ctx, m, "k", what);
    fresnel.eta = get_rgb(ctx, en, "eta");
    fresnel.k = get_rgb(ctx, kn, "k");
    if (!(fresnel.eta > 0.0f).all()) value_error(ctx, en, "'eta' components must be > 0");
  } else {
    parse_error(ctx, m, "missing required key 'reflectance' (or 'eta' and 'k') in " + what);
  }
  const float alpha = parse_roughness(ctx, m);
  return make_two_sided(make_conductor(alpha, alpha, parse_distribution(ctx, m), fresnel));
}

BsdfPtr parse_plastic(const Context& ctx, const YAML::Node& m, const std::string& what) {
  check_keys(ctx, m, {"type", "diffuse", "ior", "ext_ior", "roughness", "distribution"}, what);
  TexturePtr kd = parse_texture(ctx, require(ctx, m, "diffuse", what), "diffuse", true);
  const float ior = parse_ior(ctx, m, "ior", 1.5f, false, what);
  const float ext_ior = parse_ior(ctx, m, "ext_ior", 1.0f, false, what);
  return make_two_sided(make_plastic(std::move(kd), ior, ext_ior, parse_roughness(ctx, m), parse_distribution(ctx, m)));
}

BsdfPtr parse_material(const Context& ctx, const std::string& name, const YAML::Node& m) {
  const std::string what = "material '" + quote_input(name) + "'";
  expect_map(ctx, m, what);
  const YAML::Node type_node = require(ctx, m, "type", what);
  const std::string type = get_string(ctx, type_node, "type");
  if (type == "diffuse") return parse_diffuse(ctx, m, what);
  if (type == "phong") return parse_phong(ctx, m, what);
  if (type == "mirror") return parse_mirror(ctx, m, what);
  if (type == "dielectric") return parse_dielectric(ctx, m, what);
  if (type == "conductor") return parse_conductor(ctx, m, what);
  if (type == "plastic") return parse_plastic(ctx, m, what);
  parse_error(ctx, type_node,
              "unknown material type '" + quote_input(type) + "' (diffuse, phong, mirror, dielectric, conductor, plastic)");
}

}  // namespace

void parse_materials(LoadState& st, const YAML::Node& materials) {
  expect_map(st.ctx, materials, "materials");
  for (auto it = materials.begin(); it != materials.end(); ++it) {
    const std::string name = get_string(st.ctx, it->first, "material name");
    if (st.materials.count(name)) parse_error(st.ctx, it->first, "material '" + quote_input(name) + "' is defined twice");
    if (name == "none") parse_error(st.ctx, it->first, "material name 'none' is reserved (an index-matched medium boundary)");
    st.materials[name].bsdf = parse_material(st.ctx, name, it->second);
  }
}

int LoadState::material_index(const YAML::Node& ref) {
  const std::string name = get_string(ctx, ref, "material");
  auto it = materials.find(name);
  if (it == materials.end()) parse_error(ctx, ref, "undefined material '" + quote_input(name) + "'");
  if (it->second.index < 0) it->second.index = scene.add_bsdf(it->second.bsdf, name);
  return it->second.index;
}

}  // namespace dp::scene::yaml
