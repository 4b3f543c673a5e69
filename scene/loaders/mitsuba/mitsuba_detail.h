// Internals of the Mitsuba importer shared by mitsuba_*.cpp (not a public header).
//
// Object wraps one plugin element (<bsdf type="...">, <shape ...>, ...): its
// parameters (named value elements, named nested objects and references) are read
// through typed getters that mark them used; finish() reports every parameter nobody
// read: listed as harmless -> one warning line, otherwise a ParseError. Parameter
// names are normalized to Mitsuba 3 spelling (toWorld -> to_world, intIOR -> int_ior),
// so one code path reads both syntaxes.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/bsdf/bsdfs.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"
#include "scene/scene.h"
#include "scene/bsdf/texture.h"
#include "scene/loaders/mitsuba/xml_reader.h"

namespace dp::scene::mitsuba {

// camelCase -> snake_case (runs of capitals stay one word: intIOR -> int_ior).
std::string normalize_name(const std::string& name);
std::string where(const XmlElement& e);  // "file:line"

class Loader;

class Object {
 public:
  Object(Loader& loader, const XmlElement& element);
  const XmlElement& elem() const { return m_elem; }
  const std::string& tag() const { return m_elem.tag; }
  const std::string& type() const { return m_type; }
  std::string describe() const;  // <bsdf type="diffuse"> for messages
  Loader& loader() const { return m_loader; }

  bool has(const std::string& name) const;
  // The element of parameter `name` (nullptr if absent); marks it used.
  const XmlElement* take(const std::string& name);
  float get_float(const std::string& name, float def);
  int get_int(const std::string& name, int def);
  bool get_bool(const std::string& name, bool def);
  std::string get_string(const std::string& name, const std::string& def);
  Rgb get_rgb(const std::string& name, const Rgb& def);
  Vec3 get_point(const std::string& name, const Vec3& def);
  Mat4d get_transform(const std::string& name);  // identity if absent
  // Float, string name (Mitsuba's IOR table) or absent -> def.
  float get_ior(const std::string& name, float def);
  // rgb/srgb/spectrum/float constant, a nested or referenced texture; nullptr if absent.
  TexturePtr get_texture(const std::string& name);
  TexturePtr get_texture(const std::string& name, const Rgb& def);
  // Nested (or referenced) objects of a tag, named or unnamed, in document order;
  // marks them used. References are resolved to their target element.
  std::vector<const XmlElement*> objects(const std::string& tag);
  // A named nested object/reference (e.g. "interior"), resolved; nullptr if absent.
  const XmlElement* named_object(const std::string& name);

  // Marks a parameter as consumed with a warning that it was ignored (`why`).
  void ignore(const std::string& name, const std::string& why);
  // Reports unread parameters (see the class comment). Call once at the end.
  void finish();
  // The `value` attribute of a parameter element; a file:line error when it has none.
  const std::string& value_of(const XmlElement& e) const;
  [[noreturn]] void error(const std::string& msg) const;
  [[noreturn]] void error_at(const XmlElement& at, const std::string& msg) const;
  [[noreturn]] void value_error_at(const XmlElement& at, const std::string& msg) const;

 private:
  struct Param {
    std::string name;
    const XmlElement* elem;
    bool used = false;
  };
  Param* find(const std::string& name);

  Loader& m_loader;
  const XmlElement& m_elem;
  std::string m_type;
  std::vector<Param> m_params;  // named values and named objects / refs
  std::vector<Param> m_unnamed;  // unnamed nested objects and refs
};

// Parsing of value elements (shared by Object and the transform parser).
float parse_float(const XmlElement& e, const std::string& text);
Rgb parse_color(Loader& ld, const XmlElement& e);  // <rgb>, <srgb>, <spectrum>, <float>
Vec3 parse_vec3(const XmlElement& e);               // x/y/z or value="x y z"
Mat4d parse_transform(const XmlElement& e);         // <transform> with its operations

class Loader {
 public:
  Loader(const std::string& path, Scene& scene, const MitsubaOptions& options)
      : m_path(path), m_scene(scene), m_options(options) {}
  void build(XmlElement root);

  Scene& scene() { return m_scene; }
  void warn(const XmlElement& at, const std::string& msg);
  void info(const XmlElement& at, const std::string& msg);
  std::string resolve_path(const XmlElement& at, const std::string& file) const;
  // The element with this id, or a ParseError at `at`.
  const XmlElement& lookup(const XmlElement& at, const std::string& id) const;
  // Follows <ref> elements to their targets.
  const XmlElement& deref(const XmlElement& e) const;

  // Cached builders (each element is built once; shared by every reference).
  BsdfPtr bsdf(const XmlElement& e);
  int bsdf_index(const XmlElement& e);  // added to the scene on first use
  TexturePtr texture(const XmlElement& e);
  // Shared implicit BSDFs of shapes without one: "diffuse" (0.5, Mitsuba's default)
  // or "null" (a medium boundary).
  int builtin_bsdf(const std::string& kind);
  int medium_index(const XmlElement& e);
  HomogeneousMedium& medium(const XmlElement& e);

 private:
  void preprocess(XmlElement& scene_elem, int depth);
  void substitute(XmlElement& e) const;
  void collect_ids(const XmlElement& e);
  void build_camera(const XmlElement& sensor);
  void build_integrator(const XmlElement& e);

  std::string m_path;
  Scene& m_scene;
  const MitsubaOptions& m_options;
  std::map<std::string, std::string> m_params;
  std::map<std::string, const XmlElement*> m_ids;
  std::map<const XmlElement*, BsdfPtr> m_bsdfs;
  std::map<const XmlElement*, int> m_bsdf_index;
  std::map<const XmlElement*, TexturePtr> m_textures;
  std::map<const XmlElement*, HomogeneousMedium> m_media;
  std::map<const XmlElement*, int> m_medium_index;
  std::map<std::string, int> m_builtin_bsdfs;
  int m_spp = 0;
  XmlElement m_root;
};

// Plugin builders (mitsuba_bsdfs.cpp, mitsuba_shapes.cpp, mitsuba_emitters.cpp).
BsdfPtr build_bsdf(Loader& ld, const XmlElement& e);
TexturePtr build_texture(Loader& ld, const XmlElement& e);
HomogeneousMedium build_medium(Loader& ld, const XmlElement& e);
// Adds the shape (or, for shapegroup instances, shapes) to the scene.
void build_shape(Loader& ld, const XmlElement& e, const Mat4d& parent = Mat4d::Identity());
void build_emitter(Loader& ld, const XmlElement& e);

}  // namespace dp::scene::mitsuba
