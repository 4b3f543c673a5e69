// Mitsuba emitters that are not attached to shapes (area emitters: mitsuba_shapes.cpp).
//   point:       position or to_world, intensity (1, W/sr)
//   spot:        to_world (shines along +z), intensity (1), cutoff_angle (20 deg),
//                beam_width (3/4 cutoff). Mitsuba ramps linearly in angle between
//                beam_width and cutoff_angle, deltapath with a smoothstep of cos theta:
//                same cones, a slightly different edge profile (a warning says so)
//   directional: direction or to_world (+z), irradiance (1)
//   constant:    radiance (1)
//   envmap:      filename (lat-long EXR/PNG/JPEG), scale (1), to_world (its rotation;
//                translation is irrelevant at infinity). Same parameterization as
//                Mitsuba's envmap (emitter_environment.cpp); Mitsuba filters the map
//                bilinearly, deltapath looks up the nearest pixel
// sampling_weight is ignored with a warning (deltapath selects emitters uniformly).
#include <cmath>

#include "core/error.h"
#include "core/image_io.h"
#include "scene/limits.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"

namespace dp::scene::mitsuba {

namespace {

Vec3 apply_point(Object& o, const Mat4d& m, const Vec3& p) {
  const Vec3d w = m.block<3, 3>(0, 0) * p.cast<double>() + m.block<3, 1>(0, 3);
  if (!(w.cwiseAbs().maxCoeff() <= kMaxSceneMagnitude))
    o.value_error_at(o.elem(), std::string("light position beyond the scene limit (coordinates at most ") +
                                   kMaxSceneMagnitudeText + " in magnitude, after its to_world)");
  return w.cast<float>();
}

Vec3 z_axis(Object& o, const Mat4d& m) {
  const Vec3d d = m.block<3, 1>(0, 2);
  if (!(d.norm() > 0.0)) o.error("to_world maps +z to zero");
  return d.normalized().cast<float>();
}

Rgb nonnegative(Object& o, const std::string& name, const Rgb& def) {
  const XmlElement* at = o.take(name);
  const Rgb c = o.get_rgb(name, def);
  if (!(c >= 0.0f).all()) o.value_error_at(at ? *at : o.elem(), "'" + quote_input(name) + "' must be >= 0");
  return c;
}

EmitterPtr envmap(Loader& ld, Object& o) {
  const XmlElement* fn = o.take("filename");
  if (!fn || fn->tag != "string") o.error("envmap needs a <string name=\"filename\">");
  const std::string file = o.value_of(*fn);
  const float scale = o.get_float("scale", 1.0f);
  if (!(scale >= 0.0f)) o.value_error_at(o.elem(), "envmap 'scale' must be >= 0");
  const Mat4d m = o.get_transform("to_world");
  Eigen::Matrix3d r = m.block<3, 3>(0, 0);
  if (!((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-3) || !(r.determinant() > 0.0))
    o.error("envmap to_world must be a rotation (no scale, shear or mirror)");
  // Re-orthonormalize (matrices in files carry ~6 digits).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  r = svd.matrixU() * svd.matrixV().transpose();
  o.ignore("gamma", "the map is read as EXR (linear) or sRGB-decoded 8-bit");
  o.ignore("filter_type", "nearest-pixel lookup");
  o.ignore("cache", "loading only");
  core::Image image;
  try {
    image = core::read_image(ld.resolve_path(*fn, file));
  } catch (const Error& e) {
    throw IoError("cannot read environment map '" + quote_input(file) + "': " + e.message(), fn->file_name(), fn->line);
  }
  if (image.empty()) throw IoError("environment map '" + quote_input(file) + "' is empty", fn->file_name(), fn->line);
  for (const Rgb& c : image.pixels())
    if (!is_finite(c) || (c < 0.0f).any())
      throw ValueError("environment map '" + quote_input(file) + "' has negative or non-finite pixels", fn->file_name(), fn->line);
  return std::make_unique<EnvironmentEmitter>(std::move(image), r.cast<float>(), scale);
}

}  // namespace

void build_emitter(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  const std::string& t = o.type();
  EmitterPtr em;
  if (t == "point") {
    const Mat4d m = o.get_transform("to_world");
    const Vec3 p = o.get_point("position", Vec3::Zero());
    em = std::make_unique<PointEmitter>(apply_point(o, m, p), nonnegative(o, "intensity", Rgb::Ones()));
  } else if (t == "spot") {
    const Mat4d m = o.get_transform("to_world");
    const float cutoff = o.get_float("cutoff_angle", 20.0f);
    const float beam = o.get_float("beam_width", 0.75f * cutoff);
    if (!(cutoff > 0.0f && cutoff <= 90.0f) || !(beam >= 0.0f && beam <= cutoff))
      o.value_error_at(e, "spot needs 0 < cutoff_angle <= 90 and 0 <= beam_width <= cutoff_angle");
    if (beam < cutoff)
      ld.warn(e, "spot falloff between beam_width and cutoff_angle is a smoothstep in cos theta (Mitsuba: linear in angle)");
    em = std::make_unique<SpotEmitter>(apply_point(o, m, Vec3::Zero()), z_axis(o, m), nonnegative(o, "intensity", Rgb::Ones()),
                                       cutoff, beam);
  } else if (t == "directional") {
    Vec3 d;
    if (o.has("direction")) {
      if (o.has("to_world")) o.error("give either 'direction' or 'to_world', not both");
      d = o.get_point("direction", Vec3(0, 0, 1));
      if (!(d.norm() > 0.0f)) o.value_error_at(e, "'direction' must be non-zero");
      d.normalize();
    } else {
      d = z_axis(o, o.get_transform("to_world"));
    }
    em = std::make_unique<DirectionalEmitter>(d, nonnegative(o, "irradiance", Rgb::Ones()));
  } else if (t == "constant") {
    em = std::make_unique<EnvironmentEmitter>(nonnegative(o, "radiance", Rgb::Ones()));
  } else if (t == "envmap") {
    em = envmap(ld, o);
  } else if (t == "area") {
    o.error("an area emitter must be nested inside a <shape>");
  } else {
    o.error("unsupported emitter type '" + quote_input(t) + "' (point, spot, directional, constant, envmap; area inside a shape)");
  }
  if (em->kind() == EmitterKind::environment && ld.scene().environment())
    o.error("a scene can have only one environment emitter (constant or envmap)");
  o.ignore("sampling_weight", "light selection only (deltapath selects emitters uniformly)");
  o.finish();
  ld.scene().add_emitter(std::move(em));
}

}  // namespace dp::scene::mitsuba
