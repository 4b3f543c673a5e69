// Mitsuba media.
//   homogeneous: sigma_t (1) and albedo (0.75) — Mitsuba 3 and 0.6 — or sigma_a and
//                sigma_s (0.6), all constant colours, times scale (1); a named
//                'material' (measured media) and volume-textured coefficients are
//                errors.
//   heterogeneous: a `gridvolume` density -- `density` (0.6) or `sigma_t` (Mitsuba 3) --
//                read from its `.vol` file (scene/media/density_grid.h; 1 channel), its
//                to_world/toWorld an axis-aligned scale + translation of the file's box
//                (rotations are errors); times `scale` (1): sigma_t(x) = density(x) scale,
//                grey; `albedo` a constant colour (Mitsuba 3) or a `constvolume` (0.6),
//                default 0.75; `method` ignored (sampling technique).
//   phase:       isotropic (default), hg with g (Mitsuba's default 0.8), -1 < g < 1.
// Media are attached to shapes as interior/exterior (and to a sensor); `volpath` renders
// them (medium.h).
#include <cmath>
#include <memory>

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

// A <volume type="gridvolume">: its grid, with the box moved by its transform.
std::shared_ptr<const DensityGrid> build_grid_volume(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  if (o.type() != "gridvolume")
    o.error("unsupported volume '" + quote_input(o.type()) + "' for a heterogeneous medium's density (gridvolume)");
  const XmlElement* fn = o.take("filename");
  if (!fn || fn->tag != "string") o.error(o.describe() + " needs a <string name=\"filename\">");
  const std::string file = o.value_of(*fn);
  DensityGrid g;
  try {
    g = read_vol_file(ld.resolve_path(*fn, file));
  } catch (const IoError& err) {
    throw IoError("cannot load density grid '" + quote_input(file) + "': " + err.message(), fn->file_name(), fn->line);
  } catch (const Error& err) {
    throw ParseError("invalid density grid '" + quote_input(file) + "': " + err.message(), fn->file_name(), fn->line);
  }
  const Mat4d m = o.has("to_world") ? o.get_transform("to_world") : o.get_transform("toWorld");
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (r != c && m(r, c) != 0.0) o.error("a gridvolume's transform must be an axis-aligned scale and translation");
  for (int a = 0; a < 3; ++a) {
    const double lo = m(a, a) * double(g.lo[a]) + m(a, 3), hi = m(a, a) * double(g.hi[a]) + m(a, 3);
    g.lo[a] = float(std::min(lo, hi));
    g.hi[a] = float(std::max(lo, hi));
  }
  g.finalize(e.file_name() + ":" + std::to_string(e.line));
  o.ignore("use_grid_bbox", "the file's box is used");
  o.ignore("filter_type", "trilinear interpolation");
  o.finish();
  return std::make_shared<const DensityGrid>(std::move(g));
}

HomogeneousMedium build_heterogeneous(Loader& ld, Object& o, const XmlElement& e) {
  HomogeneousMedium m;
  if (const std::string* id = e.attribute("id")) m.name = *id;
  const XmlElement* density = o.named_object("density");
  if (!density) density = o.named_object("sigma_t");
  if (!density) o.error("a heterogeneous medium needs a <volume name=\"density\"> (or \"sigma_t\") of type gridvolume");
  m.density = build_grid_volume(ld, *density);
  const float scale = o.get_float("scale", 1.0f);
  if (!(scale > 0.0f) || !std::isfinite(scale)) o.value_error_at(e, "medium 'scale' must be > 0");
  Rgb albedo = Rgb::Constant(0.75f);
  if (const XmlElement* v = o.named_object("albedo"); v && v->tag == "volume") {
    Object c(ld, *v);
    if (c.type() != "constvolume") c.error("only a constvolume albedo is supported");
    albedo = c.get_rgb("value", albedo);
    c.finish();
  } else if (o.has("albedo")) {
    albedo = o.get_rgb("albedo", albedo);
  }
  if (!(albedo >= 0.0f).all() || !(albedo <= 1.0f).all()) o.value_error_at(e, "medium 'albedo' must be in [0, 1]");
  m.sigma_s = scale * albedo;
  m.sigma_a = Rgb::Constant(scale) - m.sigma_s;
  o.ignore("method", "sampling technique only (delta tracking)");
  return m;
}

HomogeneousMedium build_homogeneous(Object& o, const XmlElement& e) {
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
  return m;
}

}  // namespace

HomogeneousMedium build_medium(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  if (o.type() != "homogeneous" && o.type() != "heterogeneous")
    o.error("unsupported medium type '" + quote_input(o.type()) + "' (homogeneous, heterogeneous)");
  HomogeneousMedium m = o.type() == "heterogeneous" ? build_heterogeneous(ld, o, e) : build_homogeneous(o, e);
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
