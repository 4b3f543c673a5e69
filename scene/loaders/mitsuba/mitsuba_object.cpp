// Mitsuba plugin parameters: Object (see mitsuba_detail.h), value elements (<float>,
// <rgb>, <spectrum>, <point>, ...) and <transform> operations.
//
// Values: <rgb>/<srgb> take 1 or 3 numbers separated by commas and/or spaces (or
// "#rrggbb", read as sRGB); <srgb> is decoded from the sRGB curve to linear.
// <spectrum value="0.5"/> is a constant; value="400:0.1, 500:0.2, ..." (nm:value) or
// filename="x.spd" (lines "nm value") is converted with spectrum_to_rgb().
// Transforms: <translate>, <scale>, <rotate>, <matrix> (16 numbers, row-major, or 9
// for a 3x3) and <lookat origin target up> compose in document order, each one
// applied after the previous ones (M <- op * M), as in Mitsuba.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/number_syntax.h"
#include "scene/limits.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"
#include "scene/loaders/mitsuba/spectrum.h"

namespace dp::scene::mitsuba {

namespace {

bool is_value_tag(const std::string& t) {
  return t == "float" || t == "integer" || t == "boolean" || t == "string" || t == "rgb" || t == "srgb" ||
         t == "spectrum" || t == "blackbody" || t == "point" || t == "vector" || t == "transform" ||
         t == "animation";
}
bool is_object_tag(const std::string& t) {
  return t == "bsdf" || t == "texture" || t == "shape" || t == "emitter" || t == "medium" || t == "phase" ||
         t == "sampler" || t == "film" || t == "rfilter" || t == "sensor" || t == "integrator" ||
         t == "subsurface" || t == "volume";
}

[[noreturn]] void fail(const XmlElement& e, const std::string& msg) { throw ParseError(msg, e.file_name(), e.line); }

const std::string& attr(const XmlElement& e, const std::string& name) {
  const std::string* v = e.attribute(name);
  if (!v) fail(e, "<" + quote_input(e.tag) + "> needs a '" + quote_input(name) + "' attribute");
  return *v;
}

std::vector<std::string> split_numbers(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : text) {
    if (c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

std::vector<double> parse_numbers(const XmlElement& e, const std::string& text) {
  std::vector<double> out;
  for (const std::string& s : split_numbers(text)) out.push_back(double(parse_float(e, s)));
  return out;
}

Rgb parse_hex(const XmlElement& e, const std::string& text) {
  if (text.size() != 7 || text.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos)
    fail(e, "malformed colour '" + quote_input(text) + "' (expected #rrggbb)");
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = float(std::stoi(text.substr(1 + 2 * size_t(i), 2), nullptr, 16)) / 255.0f;
  return srgb_to_linear(c);
}

Rgb parse_spectrum(const XmlElement& e, const Loader& ld) {
  std::vector<std::pair<float, float>> samples;
  if (const std::string* file = e.attribute("filename")) {
    const std::string path = ld.resolve_path(e, *file);
    std::ifstream in(path);
    if (!in) throw IoError("cannot open spectrum file '" + quote_input(*file) + "'", e.file_name(), e.line);
    std::string line;
    while (std::getline(in, line)) {
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      const std::vector<std::string> parts = split_numbers(line);
      if (parts.empty()) continue;
      if (parts.size() != 2) fail(e, "spectrum file '" + quote_input(*file) + "': expected 'wavelength value' per line");
      samples.emplace_back(parse_float(e, parts[0]), parse_float(e, parts[1]));
    }
  } else {
    const std::string& text = attr(e, "value");
    if (text.find(':') == std::string::npos) {
      const std::vector<double> v = parse_numbers(e, text);
      if (v.size() != 1)
        fail(e, "<spectrum> value must be one number or a list of wavelength:value pairs (got '" + quote_input(text) + "')");
      return Rgb::Constant(float(v[0]));
    }
    for (const std::string& pair : split_numbers(text)) {
      const size_t colon = pair.find(':');
      if (colon == std::string::npos) fail(e, "malformed spectrum entry '" + quote_input(pair) + "' (expected wavelength:value)");
      samples.emplace_back(parse_float(e, pair.substr(0, colon)), parse_float(e, pair.substr(colon + 1)));
    }
  }
  if (samples.empty()) fail(e, "empty spectrum");
  for (size_t i = 1; i < samples.size(); ++i)
    if (!(samples[i].first > samples[i - 1].first)) fail(e, "spectrum wavelengths must be strictly increasing");
  return spectrum_to_rgb(samples);
}

Vec3d parse_vec3_attr(const XmlElement& e, const std::string& name) {
  const std::vector<double> v = parse_numbers(e, attr(e, name));
  if (v.size() != 3) fail(e, "'" + quote_input(name) + "' of <" + quote_input(e.tag) + "> needs 3 numbers");
  return Vec3d(v[0], v[1], v[2]);
}

// x/y/z attributes (each defaulting to `def`) or value="x y z" (or one number, for scale).
Vec3d xyz_or_value(const XmlElement& e, double def, bool allow_scalar) {
  if (const std::string* v = e.attribute("value")) {
    if (e.attribute("x") || e.attribute("y") || e.attribute("z"))
      fail(e, "<" + quote_input(e.tag) + "> takes either 'value' or x/y/z, not both");
    const std::vector<double> n = parse_numbers(e, *v);
    if (allow_scalar && n.size() == 1) return Vec3d::Constant(n[0]);
    if (n.size() != 3) fail(e, "'value' of <" + quote_input(e.tag) + "> needs 3 numbers");
    return Vec3d(n[0], n[1], n[2]);
  }
  Vec3d out = Vec3d::Constant(def);
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    if (const std::string* s = e.attribute(names[i])) out[i] = double(parse_float(e, *s));
  return out;
}

Mat4d lookat(const XmlElement& e) {
  const Vec3d origin = parse_vec3_attr(e, "origin"), target = parse_vec3_attr(e, "target");
  const Vec3d dir = target - origin;
  if (!(dir.norm() > 0.0)) fail(e, "<lookat>: origin and target coincide");
  const Vec3d d = dir.normalized();
  Vec3d up;
  if (e.attribute("up")) {
    up = parse_vec3_attr(e, "up");
  } else {  // Mitsuba 3 picks any perpendicular direction
    up = std::abs(d.x()) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  }
  const Vec3d left_raw = up.cross(d);
  if (!(left_raw.norm() > 1e-9 * up.norm())) fail(e, "<lookat>: 'up' is zero or parallel to the view direction");
  const Vec3d left = left_raw.normalized();
  const Vec3d new_up = d.cross(left);
  Mat4d m = Mat4d::Identity();
  m.block<3, 1>(0, 0) = left;
  m.block<3, 1>(0, 1) = new_up;
  m.block<3, 1>(0, 2) = d;
  m.block<3, 1>(0, 3) = origin;
  return m;
}

Mat4d transform_op(const XmlElement& op) {
  Mat4d m = Mat4d::Identity();
  if (op.tag == "translate") {
    m.block<3, 1>(0, 3) = xyz_or_value(op, 0.0, false);
  } else if (op.tag == "scale") {
    const Vec3d s = xyz_or_value(op, 1.0, true);
    m.block<3, 3>(0, 0) = s.asDiagonal();
  } else if (op.tag == "rotate") {
    const Vec3d axis = xyz_or_value(op, 0.0, false);
    if (!(axis.norm() > 0.0)) fail(op, "<rotate> needs a non-zero axis (x, y, z or value)");
    const double angle = double(parse_float(op, attr(op, "angle")));
    m.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle * kPiD / 180.0, axis.normalized()).toRotationMatrix();
  } else if (op.tag == "matrix") {
    const std::vector<double> v = parse_numbers(op, attr(op, "value"));
    if (v.size() == 16) {
      for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = v[size_t(i)];
    } else if (v.size() == 9) {
      for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[size_t(i)];
    } else {
      fail(op, "<matrix> needs 16 (or 9) numbers, got " + std::to_string(v.size()));
    }
    if (v.size() == 16 && (m(3, 0) != 0.0 || m(3, 1) != 0.0 || m(3, 2) != 0.0 || m(3, 3) != 1.0))
      fail(op, "<matrix>: projective matrices are not supported (last row must be 0 0 0 1)");
  } else if (op.tag == "lookat") {
    m = lookat(op);
  } else {
    fail(op, "unknown transform operation <" + quote_input(op.tag) + "> (translate, scale, rotate, matrix, lookat)");
  }
  if (!m.allFinite()) fail(op, "<" + quote_input(op.tag) + "> gives a non-finite matrix");
  return m;
}

}  // namespace

std::string normalize_name(const std::string& name) {
  std::string out;
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (c >= 'A' && c <= 'Z') {
      const char prev = i > 0 ? name[i - 1] : '_';
      if ((prev >= 'a' && prev <= 'z') || (prev >= '0' && prev <= '9')) out += '_';
      out += char(c - 'A' + 'a');
    } else {
      out += c;
    }
  }
  return out;
}

std::string where(const XmlElement& e) { return e.file_name() + ":" + std::to_string(e.line); }

float parse_float(const XmlElement& e, const std::string& text) {
  std::string_view s(text);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  if (!core::is_decimal_number(s)) fail(e, "'" + quote_input(text) + "' is not a number");
  const double v = std::strtod(text.c_str(), nullptr);  // skips the leading blanks
  if (!std::isfinite(v)) fail(e, "'" + quote_input(text) + "' is not a finite number");
  if (!within_scene_limit(v))
    throw ValueError("'" + quote_input(text) + "' is beyond the scene limit (magnitude at most " +
                         std::string(kMaxSceneMagnitudeText) + ")",
                     e.file_name(), e.line);
  return float(v);
}

Rgb parse_color(Loader& ld, const XmlElement& e) {
  if (e.tag == "spectrum") return parse_spectrum(e, ld);
  if (e.tag == "blackbody") fail(e, "<blackbody> spectra are not supported (give an <rgb> radiance)");
  if (e.tag == "float" || e.tag == "integer") return Rgb::Constant(parse_float(e, attr(e, "value")));
  if (e.tag != "rgb" && e.tag != "srgb") fail(e, "expected a colour (<rgb>, <srgb>, <spectrum> or <float>), got <" + quote_input(e.tag) + ">");
  const std::string& text = attr(e, "value");
  if (!text.empty() && text[0] == '#') return parse_hex(e, text);
  const std::vector<double> v = parse_numbers(e, text);
  Rgb c;
  if (v.size() == 1) c = Rgb::Constant(float(v[0]));
  else if (v.size() == 3) c = Rgb(float(v[0]), float(v[1]), float(v[2]));
  else fail(e, "<" + quote_input(e.tag) + "> needs 1 or 3 numbers, got " + std::to_string(v.size()));
  return e.tag == "srgb" ? srgb_to_linear(c) : c;
}

Vec3 parse_vec3(const XmlElement& e) { return xyz_or_value(e, 0.0, false).cast<float>(); }

Mat4d parse_transform(const XmlElement& e) {
  if (e.tag != "transform") fail(e, "expected a <transform>, got <" + quote_input(e.tag) + ">");
  Mat4d m = Mat4d::Identity();
  for (const XmlElement& op : e.children) m = transform_op(op) * m;
  return m;
}

// ---------------------------------------------------------------------------------
Object::Object(Loader& loader, const XmlElement& element) : m_loader(loader), m_elem(element) {
  if (const std::string* t = element.attribute("type")) m_type = *t;
  for (const auto& [k, v] : element.attributes)
    if (k != "type" && k != "id" && k != "name") fail(element, "unknown attribute '" + quote_input(k) + "' of " + describe());
  for (const XmlElement& c : element.children) {
    const std::string* name = c.attribute("name");
    if (c.tag == "material" && !name && c.attribute("value")) {
      // Not Mitsuba syntax (written by some exporters): <material value="bk7"/>.
      loader.warn(c, "non-Mitsuba element <material value=\"" + *c.attribute("value") +
                         "\"/> read as the 'material' parameter");
      m_params.push_back({"material", &c});
      continue;
    }
    if (is_value_tag(c.tag)) {
      if (!name) fail(c, "<" + quote_input(c.tag) + "> inside " + describe() + " needs a 'name' attribute");
    } else if (!is_object_tag(c.tag) && c.tag != "ref") {
      fail(c, "unknown element <" + quote_input(c.tag) + "> inside " + describe());
    }
    if (!name) {
      m_unnamed.push_back({"", &c});
      continue;
    }
    const std::string n = normalize_name(*name);
    if (find(n)) fail(c, "parameter '" + quote_input(n) + "' of " + describe() + " is given twice");
    m_params.push_back({n, &c});
  }
}

std::string Object::describe() const {
  return "<" + quote_input(m_elem.tag) + (m_type.empty() ? "" : " type=\"" + quote_input(m_type) + "\"") + ">";
}

Object::Param* Object::find(const std::string& name) {
  for (Param& p : m_params)
    if (p.name == name) return &p;
  return nullptr;
}

bool Object::has(const std::string& name) const {
  for (const Param& p : m_params)
    if (p.name == name) return true;
  return false;
}

const XmlElement* Object::take(const std::string& name) {
  Param* p = find(name);
  if (!p) return nullptr;
  p->used = true;
  return p->elem;
}

float Object::get_float(const std::string& name, float def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag != "float" && e->tag != "integer")
    error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a <float> (got <" + quote_input(e->tag) + ">)");
  return parse_float(*e, attr(*e, "value"));
}

int Object::get_int(const std::string& name, int def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag != "integer") error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be an <integer> (got <" + quote_input(e->tag) + ">)");
  const std::string& text = attr(*e, "value");
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < -2147483647L || v > 2147483647L)
    error_at(*e, "'" + quote_input(text) + "' is not an integer");
  return int(v);
}

bool Object::get_bool(const std::string& name, bool def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag != "boolean") error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a <boolean> (got <" + quote_input(e->tag) + ">)");
  const std::string& v = attr(*e, "value");
  if (v == "true" || v == "True" || v == "TRUE") return true;
  if (v == "false" || v == "False" || v == "FALSE") return false;
  error_at(*e, "'" + quote_input(v) + "' is not a boolean (true or false)");
}

std::string Object::get_string(const std::string& name, const std::string& def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag != "string" && !(name == "material" && e->tag == "material"))
    error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a <string> (got <" + quote_input(e->tag) + ">)");
  return attr(*e, "value");
}

Rgb Object::get_rgb(const std::string& name, const Rgb& def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag == "texture" || e->tag == "ref")
    error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a constant colour, not a texture");
  return parse_color(m_loader, *e);
}

Vec3 Object::get_point(const std::string& name, const Vec3& def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  if (e->tag != "point" && e->tag != "vector")
    error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a <point> or <vector>");
  return parse_vec3(*e);
}

Mat4d Object::get_transform(const std::string& name) {
  const XmlElement* e = take(name);
  if (!e) return Mat4d::Identity();
  if (e->tag == "animation") error_at(*e, "animated transforms are not supported");
  return parse_transform(*e);
}

float Object::get_ior(const std::string& name, float def) {
  const XmlElement* e = take(name);
  if (!e) return def;
  float v;
  if (e->tag == "string" || e->tag == "material") {
    const std::string& s = attr(*e, "value");
    const std::optional<float> ior = named_ior(s);
    if (!ior) error_at(*e, "unknown index of refraction '" + quote_input(s) + "' for '" + quote_input(name) + "' (e.g. vacuum, air, water, bk7, diamond)");
    v = *ior;
  } else if (e->tag == "float" || e->tag == "integer") {
    v = parse_float(*e, attr(*e, "value"));
  } else {
    error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a <float> or an IOR name");
  }
  if (!(v > 0.0f)) value_error_at(*e, "'" + quote_input(name) + "' must be > 0");
  return v;
}

TexturePtr Object::get_texture(const std::string& name) {
  const XmlElement* e = take(name);
  if (!e) return nullptr;
  const XmlElement& t = m_loader.deref(*e);
  if (t.tag == "texture") return m_loader.texture(t);
  if (t.tag == "rgb" || t.tag == "srgb" || t.tag == "spectrum" || t.tag == "float" || t.tag == "integer")
    return constant_texture(parse_color(m_loader, t));
  error_at(*e, "parameter '" + quote_input(name) + "' of " + describe() + " must be a colour or a texture (got <" + quote_input(t.tag) + ">)");
}

TexturePtr Object::get_texture(const std::string& name, const Rgb& def) {
  TexturePtr t = get_texture(name);
  return t ? t : constant_texture(def);
}

std::vector<const XmlElement*> Object::objects(const std::string& tag) {
  std::vector<const XmlElement*> out;
  auto visit = [&](Param& p) {
    const XmlElement& target = m_loader.deref(*p.elem);
    if (target.tag != tag) return;
    p.used = true;
    out.push_back(&target);
  };
  for (Param& p : m_unnamed) visit(p);
  for (Param& p : m_params)
    if (is_object_tag(p.elem->tag) || p.elem->tag == "ref") visit(p);
  return out;
}

const XmlElement* Object::named_object(const std::string& name) {
  const XmlElement* e = take(name);
  return e ? &m_loader.deref(*e) : nullptr;
}

void Object::ignore(const std::string& name, const std::string& why) {
  if (const XmlElement* e = take(name)) m_loader.warn(*e, describe() + " parameter '" + quote_input(name) + "' ignored: " + why);
}

void Object::finish() {
  for (const Param& p : m_params)
    if (!p.used)
      error_at(*p.elem, "unsupported parameter '" + quote_input(p.name) + "' (<" + p.elem->tag + ">) of " + describe());
  for (const Param& p : m_unnamed)
    if (!p.used) {
      const XmlElement& t = m_loader.deref(*p.elem);
      error_at(*p.elem, "unexpected <" + t.tag + (t.attribute("type") ? " type=\"" + *t.attribute("type") + "\"" : "") +
                            "> inside " + describe());
    }
}

void Object::error(const std::string& msg) const { fail(m_elem, msg); }
void Object::error_at(const XmlElement& at, const std::string& msg) const { fail(at, msg); }
const std::string& Object::value_of(const XmlElement& e) const { return attr(e, "value"); }
void Object::value_error_at(const XmlElement& at, const std::string& msg) const {
  throw ValueError(msg, at.file_name(), at.line);
}

}  // namespace dp::scene::mitsuba
