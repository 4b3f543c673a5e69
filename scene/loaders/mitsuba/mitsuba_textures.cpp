// Mitsuba textures.
//   bitmap:       filename (PNG/JPEG decoded sRGB -> linear unless raw=true; EXR linear),
//                 to_uv (affine 2D); filter_type, max_anisotropy, cache are ignored with
//                 a warning (bilinear lookup, no MIP-mapping: identical where texels are
//                 larger than pixels); wrap_mode other than repeat is an error
//   checkerboard: color0 (0.4), color1 (0.2), to_uv or (0.6) uscale/vscale/uoffset/
//                 voffset; Mitsuba 3's pattern: color0 where frac(u) and frac(v) are on
//                 the same side of 1/2 (Mitsuba 0.6 agrees for u, v >= 0)
// UV convention: deltapath meshes carry uv with v = 0 at the bottom of an image
// (texture.h); Mitsuba's v = 0 is the top row. The shape builders store (u, 1 - v_mts),
// so a bitmap looks the same, and the textures below evaluate Mitsuba's formulas at
// (u, 1 - v), i.e. at Mitsuba's own coordinates.
#include <cmath>
#include <memory>

#include "core/error.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"

namespace dp::scene::mitsuba {

namespace {

// 2D affine map applied to Mitsuba's uv: uv' = A uv + b.
struct UvTransform {
  Eigen::Matrix2f a = Eigen::Matrix2f::Identity();
  Vec2 b = Vec2::Zero();
  bool identity() const { return a.isIdentity(0.0f) && b.isZero(0.0f); }
  Vec2 apply(const Vec2& ours) const { return a * Vec2(ours.x(), 1.0f - ours.y()) + b; }
};

class MitsubaCheckerboard final : public Texture {
 public:
  MitsubaCheckerboard(const Rgb& c0, const Rgb& c1, const UvTransform& xf) : m_c0(c0), m_c1(c1), m_xf(xf) {}
  Rgb eval(const Vec2& uv) const override {
    const Vec2 m = m_xf.apply(uv);
    const float fu = m.x() - std::floor(m.x()), fv = m.y() - std::floor(m.y());
    return ((fu > 0.5f) == (fv > 0.5f)) ? m_c0 : m_c1;
  }
  Rgb mean() const override { return 0.5f * (m_c0 + m_c1); }
  Rgb max() const override { return m_c0.max(m_c1); }

 private:
  Rgb m_c0, m_c1;
  UvTransform m_xf;
};

// A bitmap looked up at transformed Mitsuba coordinates.
class TransformedTexture final : public Texture {
 public:
  TransformedTexture(TexturePtr inner, const UvTransform& xf) : m_inner(std::move(inner)), m_xf(xf) {}
  Rgb eval(const Vec2& uv) const override {
    const Vec2 m = m_xf.apply(uv);
    return m_inner->eval(Vec2(m.x(), 1.0f - m.y()));
  }
  Rgb mean() const override { return m_inner->mean(); }
  Rgb max() const override { return m_inner->max(); }

 private:
  TexturePtr m_inner;
  UvTransform m_xf;
};

UvTransform parse_uv_transform(Object& o) {
  UvTransform xf;
  if (const XmlElement* t = o.take("to_uv")) {
    const Mat4d m = parse_transform(*t);
    if (m(0, 2) != 0.0 || m(1, 2) != 0.0 || m(2, 0) != 0.0 || m(2, 1) != 0.0)
      o.error_at(*t, "'to_uv' must be a 2D transform (it mixes in the z axis)");
    xf.a << float(m(0, 0)), float(m(0, 1)), float(m(1, 0)), float(m(1, 1));
    xf.b = Vec2(float(m(0, 3)), float(m(1, 3)));
  }
  const float us = o.get_float("uscale", 1.0f), vs = o.get_float("vscale", 1.0f);
  const float uvs = o.get_float("uvscale", 1.0f);
  const float uo = o.get_float("uoffset", 0.0f), vo = o.get_float("voffset", 0.0f);
  // Mitsuba 0.6 Texture2D: uv' = uv * scale + offset.
  xf.a = Eigen::Vector2f(us * uvs, vs * uvs).asDiagonal() * xf.a;
  xf.b = Vec2(us * uvs * xf.b.x() + uo, vs * uvs * xf.b.y() + vo);
  return xf;
}

TexturePtr build_bitmap(Loader& ld, Object& o) {
  const XmlElement* fn = o.take("filename");
  if (!fn || fn->tag != "string") o.error("bitmap texture needs a <string name=\"filename\">");
  const std::string file = o.value_of(*fn);
  const bool raw = o.get_bool("raw", false);
  const std::string wrap = o.get_string("wrap_mode", "repeat");
  if (wrap != "repeat") o.error_at(o.elem(), "wrap_mode '" + quote_input(wrap) + "' is not supported (repeat)");
  if (o.has("gamma")) {
    const float g = o.get_float("gamma", 0);
    if (g != -1.0f && g != 0.0f) o.error_at(o.elem(), "bitmap 'gamma' other than the sRGB default is not supported");
  }
  for (const char* p : {"filter_type", "max_anisotropy", "cache", "format", "accel"})
    o.ignore(p, "bilinear lookup without MIP-mapping (texture filtering only)");
  const UvTransform xf = parse_uv_transform(o);
  TexturePtr tex;
  try {
    tex = std::make_shared<BitmapTexture>(ld.resolve_path(*fn, file), 1.0f, raw);
  } catch (const Error& e) {
    throw IoError("cannot read texture '" + quote_input(file) + "': " + e.message(), fn->file_name(), fn->line);
  }
  return xf.identity() ? tex : std::make_shared<TransformedTexture>(tex, xf);
}

}  // namespace

TexturePtr build_texture(Loader& ld, const XmlElement& e) {
  Object o(ld, e);
  TexturePtr out;
  if (o.type() == "bitmap") {
    out = build_bitmap(ld, o);
  } else if (o.type() == "checkerboard") {
    const Rgb c0 = o.get_rgb("color0", Rgb::Constant(0.4f));
    const Rgb c1 = o.get_rgb("color1", Rgb::Constant(0.2f));
    out = std::make_shared<MitsubaCheckerboard>(c0, c1, parse_uv_transform(o));
  } else {
    o.error("unsupported texture type '" + quote_input(o.type()) + "' (bitmap, checkerboard)");
  }
  o.finish();
  return out;
}

}  // namespace dp::scene::mitsuba
