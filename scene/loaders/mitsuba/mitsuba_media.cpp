// Mitsuba media.
//   homogeneous: sigma_t (1) and albedo (0.75) — Mitsuba 3 and 0.6 — or sigma_a and
//                sigma_s (0.6), all constant colours, times scale (1); a named
//                'material' (measured media) and volume-textured coefficients are
//                errors.
//   phase:       isotropic (default), hg with g (Mitsuba's default 0.8), -1 < g < 1.
// Media are attached to shapes as interior/exterior (and to a sensor); `volpath` renders
// them (medium.h).
#include <cmath>

#include "core/error.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"

namespace dp::scene::mitsuba {

namespace {

PhaseFunctionDesc build_phase(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  PhaseFunctionDesc p;
  if (o.type() == "isotropic") {
    p.type = PhaseFunctionDesc::Type::isotropic;
  } else if (o.type() == "hg") {
    p.type = PhaseFunctionDesc::Type::hg;
    p.g = o.get_float("g", 0.8f);
    if (!(std::abs(p.g) < 1.0f)) o.value_error_at(e, "hg 'g' must satisfy -1 < g < 1");
  } else {
    o.error("unsupported phase function '" + quote_input(o.type()) + "' (isotropic, hg)");
  }
  o.finish();
  return p;
}

}  // namespace

HomogeneousMedium build_medium(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  if (o.type() != "homogeneous") o.error("unsupported medium type '" + quote_input(o.type()) + "' (homogeneous)");
  if (o.has("material")) o.error_at(*o.take("material"), "named (measured) media are not supported: give sigma_t and albedo");
  HomogeneousMedium m;
  if (const std::string* id = e.attribute("id")) m.name = *id;
  const float scale = o.get_float("scale", o.get_float("density_multiplier", 1.0f));
  if (!(scale >= 0.0f)) o.value_error_at(e, "medium 'scale' must be >= 0");
  if (o.has("sigma_a") || o.has("sigma_s")) {
    if (o.has("sigma_t") || o.has("albedo")) o.error("give either sigma_a/sigma_s or sigma_t/albedo, not both");
    if (!o.has("sigma_a") || !o.has("sigma_s")) o.error("give both sigma_a and sigma_s");
    m.sigma_a = o.get_rgb("sigma_a", Rgb::Zero()) * scale;
    m.sigma_s = o.get_rgb("sigma_s", Rgb::Zero()) * scale;
  } else {
    const Rgb sigma_t = o.get_rgb("sigma_t", Rgb::Ones()) * scale;
    const Rgb albedo = o.get_rgb("albedo", Rgb::Constant(0.75f));
    if (!(albedo >= 0.0f).all() || !(albedo <= 1.0f).all()) o.value_error_at(e, "medium 'albedo' must be in [0, 1]");
    m.sigma_s = sigma_t * albedo;
    m.sigma_a = sigma_t - m.sigma_s;
  }
  if (!(m.sigma_a >= 0.0f).all() || !(m.sigma_s >= 0.0f).all() || !is_finite(m.sigma_a) || !is_finite(m.sigma_s))
    o.value_error_at(e, "medium coefficients must be finite and >= 0");
  const std::vector<const XmlElement*> phases = o.objects("phase");
  if (phases.size() > 1) o.error("a medium can have at most one phase function");
  if (!phases.empty()) m.phase = build_phase(ld, *phases[0]);
  o.ignore("sample_emitters", "sampling technique only");
  o.ignore("has_spectral_extinction", "RGB rendering");
  o.finish();
  return m;
}

}  // namespace dp::scene::mitsuba
