// Mitsuba XML front end (mitsuba_loader.h): the document (version, <include>,
// <default> + $name substitution, ids and <ref>s), the sensor and the integrator; the
// plugins are built in mitsuba_bsdfs.cpp, mitsuba_textures.cpp, mitsuba_shapes.cpp,
// mitsuba_emitters.cpp and mitsuba_media.cpp.
//
// Supported subset (both 0.5/0.6 camelCase and 3.x snake_case parameter names):
//   scene      version 0.x, 2.x or 3.x; <include filename>, <default name value>,
//              $name in any attribute, <alias id as>, ids on any object, <ref id>
//   sensor     perspective: fov + fov_axis (x, y, diagonal, smaller, larger; default
//              x) or focal_length ("50mm", 35 mm film diagonal); to_world (a rigid
//              camera frame: no mirror); near/far clip, focus distance and shutter
//              are ignored (pinhole, no clipping, no motion) with a warning
//   film       hdrfilm, ldrfilm, multifilm, tiledhdrfilm: width, height (default
//              768x576); output-format parameters and the reconstruction filter are
//              ignored with a warning (deltapath writes EXR + PNG with a one-pixel box
//              filter: sharper pixels, same image mean); crops are errors
//   sampler    any type: sample_count -> the scene's default spp
//   integrator max_depth (-1 = unbounded, mapped to 1000 segments with Russian
//              roulette), rr_depth, hide_emitters -> the path integrator's settings.
//              Other integrator types become "path" with a warning (same converged
//              image for surfaces; no integrator renders media yet)
// Shapes, BSDFs, textures, emitters and media: see their files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "scene/limits.h"
#include "scene/loaders/mitsuba/mitsuba_detail.h"

namespace dp::scene {

namespace mitsuba {

namespace {
constexpr int kMaxIncludeDepth = 16;
constexpr int kUnboundedDepth = 1000;

[[noreturn]] void fail(const XmlElement& e, const std::string& msg) { throw ParseError(msg, e.file_name(), e.line); }

bool is_identifier_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}
}  // namespace

void Loader::warn(const XmlElement& at, const std::string& msg) {
  const std::string line = where(at) + ": " + msg;
  log::warn(line);
  if (m_options.warnings) m_options.warnings->push_back(line);
}

void Loader::info(const XmlElement& at, const std::string& msg) { log::info(where(at), ": ", msg); }

std::string Loader::resolve_path(const XmlElement& at, const std::string& file) const {
  namespace fs = std::filesystem;
  const fs::path p(file);
  if (p.is_absolute()) return file;
  // The error_code overloads: a name the system rejects (too long, ...) is left for
  // the reader's one-line IoError instead of a filesystem_error quoting it in full.
  std::error_code ec;
  const fs::path own = fs::path(at.file_name()).parent_path() / p;
  if (fs::exists(own, ec)) return own.string();
  const fs::path main = fs::path(m_path).parent_path() / p;
  return fs::exists(main, ec) ? main.string() : own.string();
}

const XmlElement& Loader::lookup(const XmlElement& at, const std::string& id) const {
  auto it = m_ids.find(id);
  if (it == m_ids.end()) fail(at, "reference to undefined id '" + quote_input(id) + "'");
  return *it->second;
}

const XmlElement& Loader::deref(const XmlElement& e) const {
  if (e.tag != "ref") return e;
  const std::string* id = e.attribute("id");
  if (!id) fail(e, "<ref> needs an 'id' attribute");
  for (const auto& [k, v] : e.attributes)
    if (k != "id" && k != "name") fail(e, "unknown attribute '" + quote_input(k) + "' of <ref>");
  return lookup(e, *id);
}

BsdfPtr Loader::bsdf(const XmlElement& e) {
  if (e.tag != "bsdf") fail(e, "expected a <bsdf>, got <" + quote_input(e.tag) + ">");
  auto it = m_bsdfs.find(&e);
  if (it != m_bsdfs.end()) return it->second;
  BsdfPtr b = build_bsdf(*this, e);
  m_bsdfs.emplace(&e, b);
  return b;
}

int Loader::bsdf_index(const XmlElement& e) {
  auto it = m_bsdf_index.find(&e);
  if (it != m_bsdf_index.end()) return it->second;
  const std::string* id = e.attribute("id");
  const int index = m_scene.add_bsdf(bsdf(e), id ? *id : e.attribute("type") ? *e.attribute("type") : "bsdf");
  m_bsdf_index.emplace(&e, index);
  return index;
}

int Loader::builtin_bsdf(const std::string& kind) {
  auto it = m_builtin_bsdfs.find(kind);
  if (it != m_builtin_bsdfs.end()) return it->second;
  BsdfPtr b = kind == "null" ? make_null() : make_diffuse(constant_texture(Rgb::Constant(0.5f)));
  const int index = m_scene.add_bsdf(b, "mitsuba-default-" + kind);
  m_builtin_bsdfs.emplace(kind, index);
  return index;
}

TexturePtr Loader::texture(const XmlElement& e) {
  if (e.tag != "texture") fail(e, "expected a <texture>, got <" + quote_input(e.tag) + ">");
  auto it = m_textures.find(&e);
  if (it != m_textures.end()) return it->second;
  TexturePtr t = build_texture(*this, e);
  m_textures.emplace(&e, t);
  return t;
}

HomogeneousMedium& Loader::medium(const XmlElement& e) {
  if (e.tag != "medium") fail(e, "expected a <medium>, got <" + quote_input(e.tag) + ">");
  auto it = m_media.find(&e);
  if (it != m_media.end()) return it->second;
  return m_media.emplace(&e, build_medium(*this, e)).first->second;
}

int Loader::medium_index(const XmlElement& e) {
  auto it = m_medium_index.find(&e);
  if (it != m_medium_index.end()) return it->second;
  const int index = m_scene.add_medium(medium(e));
  m_medium_index.emplace(&e, index);
  return index;
}

// <default>s (first definition wins; options override) and <include>s, in place.
void Loader::preprocess(XmlElement& scene_elem, int depth) {
  std::vector<XmlElement> out;
  for (XmlElement& c : scene_elem.children) {
    if (c.tag == "default") {
      const std::string* name = c.attribute("name");
      const std::string* value = c.attribute("value");
      if (!name || !value) fail(c, "<default> needs 'name' and 'value' attributes");
      m_params.emplace(*name, *value);  // no-op if already set
    } else if (c.tag == "include") {
      if (depth >= kMaxIncludeDepth) fail(c, "<include> nested too deeply (a cycle?)");
      const std::string* file = c.attribute("filename");
      if (!file) fail(c, "<include> needs a 'filename' attribute");
      std::string name = *file;
      if (name.find('$') != std::string::npos) substitute(c), name = *c.attribute("filename");
      const std::string path = resolve_path(c, name);
      XmlElement inc;
      try {
        inc = parse_xml_file(path);
      } catch (const IoError& e) {
        throw IoError("cannot read included file '" + quote_input(name) + "': " + e.message(), c.file_name(), c.line);
      }
      if (inc.tag != "scene") fail(inc, "an included file must have a <scene> root element");
      preprocess(inc, depth + 1);
      for (XmlElement& ic : inc.children) out.push_back(std::move(ic));
    } else {
      out.push_back(std::move(c));
    }
  }
  scene_elem.children = std::move(out);
}

void Loader::substitute(XmlElement& e) const {
  for (auto& [k, v] : e.attributes) {
    size_t pos = 0;
    while ((pos = v.find('$', pos)) != std::string::npos) {
      size_t end = pos + 1;
      while (end < v.size() && is_identifier_char(v[end])) ++end;
      const std::string name = v.substr(pos + 1, end - pos - 1);
      if (name.empty()) fail(e, "'$' without a parameter name in attribute '" + quote_input(k) + "'");
      auto it = m_params.find(name);
      if (it == m_params.end()) fail(e, "undefined parameter '$" + name + "' (no <default name=\"" + name + "\">)");
      v.replace(pos, end - pos, it->second);
      pos += it->second.size();
    }
  }
  for (XmlElement& c : e.children) substitute(c);
}

void Loader::collect_ids(const XmlElement& e) {
  for (const XmlElement& c : e.children) {
    if (c.tag == "alias") continue;
    if (c.tag != "ref")
      if (const std::string* id = c.attribute("id")) {
        if (!m_ids.emplace(*id, &c).second)
          fail(c, "duplicate id '" + quote_input(*id) + "' (first defined at " + where(*m_ids[*id]) + ")");
      }
    collect_ids(c);
  }
  for (const XmlElement& c : e.children)
    if (c.tag == "alias") {
      const std::string* id = c.attribute("id");
      const std::string* as = c.attribute("as");
      if (!id || !as) fail(c, "<alias> needs 'id' and 'as' attributes");
      const XmlElement& target = lookup(c, *id);
      if (!m_ids.emplace(*as, &target).second) fail(c, "duplicate id '" + quote_input(*as) + "'");
    }
}

void Loader::build_camera(const XmlElement& sensor) {
  Object o(*this, sensor);
  if (o.type() != "perspective")
    o.error("unsupported sensor type '" + quote_input(o.type()) + "' (perspective; thin-lens blur, orthographic and other "
            "projections would change the image)");
  CameraDesc desc;
  int width = 768, height = 576;
  for (const XmlElement* film_elem : o.objects("film")) {
    Object f(*this, *film_elem);
    const std::string& t = f.type();
    if (t != "hdrfilm" && t != "ldrfilm" && t != "multifilm" && t != "tiledhdrfilm")
      f.error("unsupported film type '" + quote_input(t) + "' (hdrfilm, ldrfilm, multifilm, tiledhdrfilm)");
    width = f.get_int("width", width);
    height = f.get_int("height", height);
    if (!valid_image_size(width, height))
      f.value_error_at(*film_elem,
                       "film width and height must be between 1 and 65536, at most 67108864 pixels (8192 x 8192) in total");
    for (const char* c : {"crop_offset_x", "crop_offset_y", "crop_width", "crop_height"})
      if (f.has(c)) f.error_at(*f.take(c), std::string("film crops ('") + c + "') are not supported");
    for (const char* p : {"file_format", "pixel_format", "component_format", "gamma", "banner", "high_quality_edges",
                          "attach_log", "tonemap_method", "exposure", "sample_border", "dithering", "label"})
      f.ignore(p, "output encoding only (deltapath writes EXR + PNG)");
    for (const XmlElement* rf : f.objects("rfilter")) {
      const std::string* rt = rf->attribute("type");
      if (!rt || *rt != "box")
        warn(*rf, "reconstruction filter '" + (rt ? *rt : std::string("?")) +
                      "' replaced by the one-pixel box filter (pixel-scale sharpness and noise only)");
    }
    f.finish();
  }
  for (const XmlElement* s : o.objects("sampler")) {
    Object so(*this, *s);
    m_spp = so.get_int("sample_count", 4);
    if (m_spp < 1) so.value_error_at(*s, "'sample_count' must be >= 1");
    for (const char* p : {"scramble", "seed", "dimension", "jitter", "strength", "randomize", "pixel_samples"})
      so.ignore(p, "sampling pattern only");
    so.finish();
  }
  for (const XmlElement* m : o.objects("medium")) m_scene.set_camera_medium(medium_index(*m));
  if (const XmlElement* m = o.named_object("medium")) m_scene.set_camera_medium(medium_index(*m));

  const Mat4d m = o.get_transform("to_world");
  const Vec3d left = m.block<3, 1>(0, 0), up = m.block<3, 1>(0, 1), fwd = m.block<3, 1>(0, 2);
  if (!(fwd.norm() > 0.0) || !(up.norm() > 0.0) || !(left.norm() > 0.0))
    o.error("sensor to_world is singular");
  const Vec3d f = fwd.normalized(), u = up.normalized();
  if (std::abs(f.dot(u)) > 1e-3) o.error("sensor to_world is sheared (its up and view axes are not orthogonal)");
  // Mitsuba's image x axis runs along -to_world(1, 0, 0); ours along forward x up.
  if (!(-left.normalized().dot(f.cross(u)) > 0.0))
    o.error("sensor to_world mirrors the image (negative determinant), which the camera cannot represent");
  if (!(m.block<3, 1>(0, 3).cwiseAbs().maxCoeff() <= kMaxSceneMagnitude))
    o.value_error_at(o.elem(), std::string("sensor position beyond the scene limit (coordinates at most ") +
                                   kMaxSceneMagnitudeText + " in magnitude)");
  desc.position = m.block<3, 1>(0, 3).cast<float>();
  desc.look_at = (m.block<3, 1>(0, 3) + f).cast<float>();
  desc.up = u.cast<float>();
  desc.width = width;
  desc.height = height;

  std::string axis = o.get_string("fov_axis", "x");
  double fov;
  if (o.has("fov")) {
    if (o.has("focal_length")) o.error("give either 'fov' or 'focal_length', not both");
    fov = double(o.get_float("fov", 0));
  } else {
    std::string fl = o.get_string("focal_length", "50mm");
    if (fl.size() > 2 && fl.compare(fl.size() - 2, 2, "mm") == 0) fl.resize(fl.size() - 2);
    const double mm = double(parse_float(sensor, fl));
    if (!(mm > 0.0)) o.error("'focal_length' must be > 0");
    fov = 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / kPiD;  // 35 mm film diagonal
    axis = "diagonal";
  }
  if (!(fov > 0.0 && fov < 180.0)) o.error("'fov' must be in (0, 180) degrees");
  if (axis == "smaller") axis = width <= height ? "x" : "y";
  if (axis == "larger") axis = width >= height ? "x" : "y";
  if (axis == "diagonal") {
    const double t = std::tan(0.5 * fov * kPiD / 180.0) * double(width) / std::hypot(double(width), double(height));
    fov = 2.0 * std::atan(t) * 180.0 / kPiD;
    axis = "x";
  }
  if (axis != "x" && axis != "y") o.error("'fov_axis' must be x, y, diagonal, smaller or larger (got '" + quote_input(axis) + "')");
  desc.fov_deg = float(fov);
  desc.fov_axis_x = axis == "x";
  for (const char* p : {"near_clip", "far_clip", "focus_distance", "shutter_open", "shutter_close", "principal_point_offset_x",
                        "principal_point_offset_y"})
    if (o.has(p)) {
      const bool harmless = std::string(p).find("principal") == std::string::npos;
      if (!harmless) o.error_at(*o.take(p), std::string("'") + p + "' (off-centre projection) is not supported");
      o.ignore(p, "pinhole camera without clipping planes or motion");
    }
  o.finish();
  try {
    m_scene.set_camera(desc);
  } catch (const Error& e) {
    throw ValueError(e.message(), sensor.file_name(), sensor.line);
  }
}

void Loader::build_integrator(const XmlElement& e) {
  Object o(*this, e);
  IntegratorDefaults d;
  const std::string& t = o.type();
  if (t != "path" && t != "volpath" && t != "volpath_simple") {
    warn(e, "integrator '" + quote_input(t) + "' is not available: the scene's default becomes 'path' (choose another with --integrator)");
    for (const XmlElement& c : e.children)
      if (const std::string* n = c.attribute("name")) o.take(normalize_name(*n));
    (void)o.objects("integrator");
  }
  const int depth = o.get_int("max_depth", -1);
  if (depth == 0 || depth < -1) o.value_error_at(*o.take("max_depth"), "'max_depth' must be -1 or >= 1");
  d.max_depth = depth < 0 ? kUnboundedDepth : depth;
  if (o.has("rr_depth")) {
    const int rr = o.get_int("rr_depth", 5);
    if (rr < 1) o.value_error_at(*o.take("rr_depth"), "'rr_depth' must be >= 1");
    d.settings["rr_depth"] = std::to_string(rr);
  }
  if (o.has("hide_emitters")) d.settings["hide_emitters"] = o.get_bool("hide_emitters", false) ? "true" : "false";
  o.ignore("strict_normals", "deltapath always rejects directions on inconsistent sides of shading/geometric normals");
  o.ignore("samples_per_pass", "scheduling only");
  o.ignore("block_size", "scheduling only");
  o.finish();
  d.type = t == "volpath" || t == "volpath_simple" ? "volpath" : "path";  // volpath: homogeneous media (issue 15)
  d.spp = m_spp;
  m_scene.set_integrator_defaults(d);
}

void Loader::build(XmlElement root) {
  m_root = std::move(root);
  if (m_root.tag != "scene") fail(m_root, "the root element must be <scene> (got <" + quote_input(m_root.tag) + ">)");
  const std::string* version = m_root.attribute("version");
  if (!version) fail(m_root, "<scene> needs a 'version' attribute (e.g. 0.6.0 or 3.0.0)");
  const int major = std::atoi(version->c_str());
  if (version->empty() || !std::isdigit((unsigned char)(*version)[0]) || major > 3)
    fail(m_root, "unsupported scene version '" + quote_input(*version) + "' (0.x, 2.x or 3.x)");
  for (const auto& [k, v] : m_options.parameters) m_params[k] = v;
  preprocess(m_root, 0);
  substitute(m_root);
  collect_ids(m_root);

  const XmlElement* sensor = nullptr;
  const XmlElement* integrator = nullptr;
  for (const XmlElement& c : m_root.children) {
    if (c.tag == "sensor") {
      if (sensor) warn(c, "only the first <sensor> is used");
      else sensor = &c;
    } else if (c.tag == "integrator") {
      if (integrator) warn(c, "only the first <integrator> is used");
      else integrator = &c;
    }
  }
  if (!sensor) fail(m_root, "the scene has no <sensor> (camera)");
  build_camera(*sensor);
  if (integrator) {
    build_integrator(*integrator);
  } else {
    IntegratorDefaults d;
    d.max_depth = kUnboundedDepth;  // Mitsuba's default integrator: path, unbounded depth
    d.spp = m_spp;
    m_scene.set_integrator_defaults(d);
  }

  for (const XmlElement& c : m_root.children) {
    if (c.tag == "sensor" || c.tag == "integrator" || c.tag == "alias") continue;
    if (c.tag == "bsdf") {
      bsdf(c);  // validated even if unused; added to the scene when a shape uses it
    } else if (c.tag == "texture") {
      texture(c);
    } else if (c.tag == "medium") {
      medium(c);
    } else if (c.tag == "shape") {
      const std::string* type = c.attribute("type");
      if (!type || *type != "shapegroup") build_shape(*this, c);
    } else if (c.tag == "emitter") {
      build_emitter(*this, c);
    } else if (c.tag == "phase" || c.tag == "rfilter" || c.tag == "sampler" || c.tag == "film") {
      if (!c.attribute("id")) warn(c, "<" + quote_input(c.tag) + "> at scene level without an id is ignored");
    } else {
      fail(c, "unknown or unsupported element <" + quote_input(c.tag) + "> in <scene>");
    }
  }
  if (m_scene.emitters().empty()) log::warn(m_path, ": the scene has no emitters (it will render black)");
}

}  // namespace mitsuba

namespace {
std::unique_ptr<Scene> build_scene(XmlElement root, const std::string& path, const MitsubaOptions& options) {
  auto scene = std::make_unique<Scene>();
  scene->set_source(path);
  mitsuba::Loader loader(path, *scene, options);
  loader.build(std::move(root));
  try {
    scene->commit();
  } catch (const Error& e) {
    throw ValueError(e.message(), path, 0);
  }
  return scene;
}
}  // namespace

std::unique_ptr<Scene> load_scene_mitsuba(const std::string& path) { return load_scene_mitsuba(path, {}); }

std::unique_ptr<Scene> load_scene_mitsuba(const std::string& path, const MitsubaOptions& options) {
  return build_scene(parse_xml_file(path), path, options);
}

std::unique_ptr<Scene> load_scene_mitsuba_string(const std::string& xml, const std::string& path,
                                                 const MitsubaOptions& options) {
  return build_scene(parse_xml(xml, path), path, options);
}

}  // namespace dp::scene
