// PLY reader (Turk's format): ascii, binary_little_endian and binary_big_endian.
// Scalar types: char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32,
// uint/uint32, float/float32, double/float64 — any of them for any property.
// Used: element `vertex` with x y z, optional nx ny nz, optional u v | s t |
// texture_u texture_v | texture_s texture_t; element `face` with a list property
// vertex_indices (or vertex_index), polygons fan-triangulated. Every other element and
// property is read and skipped. Errors name the file and, for ascii, the line.
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/read_file.h"
#include "scene/loaders/mesh_io.h"

namespace dp::scene {

namespace {

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 0;
}

bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

bool parse_type(const std::string& s, PlyType& t) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::i8},   {"int8", PlyType::i8},     {"uchar", PlyType::u8},   {"uint8", PlyType::u8},
      {"short", PlyType::i16}, {"int16", PlyType::i16},   {"ushort", PlyType::u16}, {"uint16", PlyType::u16},
      {"int", PlyType::i32},   {"int32", PlyType::i32},   {"uint", PlyType::u32},   {"uint32", PlyType::u32},
      {"float", PlyType::f32}, {"float32", PlyType::f32}, {"double", PlyType::f64}, {"float64", PlyType::f64}};
  for (const auto& [name, type] : kNames)
    if (s == name) {
      t = type;
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  PlyType type = PlyType::f32;
  bool is_list = false;
  PlyType count_type = PlyType::u8;
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> props;
};

enum class Format { ascii, binary_le, binary_be };

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;
  int body_line = 0;  // 1-based line where the ascii body starts
};

Header parse_header(const std::string& data, const std::string& path) {
  Header h;
  size_t pos = 0;
  int line = 0;
  bool have_format = false;
  for (;;) {
    if (pos >= data.size()) throw ParseError("PLY header has no end_header", path, line);
    size_t eol = data.find('\n', pos);
    if (eol == std::string::npos) eol = data.size();
    std::string text = data.substr(pos, eol - pos);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    pos = eol + 1;
    ++line;
    std::istringstream ls(text);
    std::string kw;
    ls >> kw;
    if (line == 1) {
      if (kw != "ply") throw ParseError("not a PLY file (missing 'ply' magic)", path, 1);
      continue;
    }
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      std::string fmt, version;
      ls >> fmt >> version;
      if (fmt == "ascii") h.format = Format::ascii;
      else if (fmt == "binary_little_endian") h.format = Format::binary_le;
      else if (fmt == "binary_big_endian") h.format = Format::binary_be;
      else throw ParseError("unknown PLY format '" + quote_input(fmt) + "'", path, line);
      if (version != "1.0") throw ParseError("unsupported PLY version '" + quote_input(version) + "'", path, line);
      have_format = true;
    } else if (kw == "element") {
      Element e;
      std::string count;
      ls >> e.name >> count;
      char* end = nullptr;
      const unsigned long long c = std::strtoull(count.c_str(), &end, 10);
      if (e.name.empty() || count.empty() || *end != '\0' || count[0] == '-')
        throw ParseError("malformed element line '" + quote_input(text) + "'", path, line);
      e.count = size_t(c);
      h.elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (h.elements.empty()) throw ParseError("property before any element", path, line);
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.is_list = true;
        if (!parse_type(ct, p.count_type) || !is_integer(p.count_type) || !parse_type(it, p.type))
          throw ParseError("malformed list property '" + quote_input(text) + "'", path, line);
      } else {
        ls >> p.name;
        if (!parse_type(t, p.type)) throw ParseError("unknown property type '" + quote_input(t) + "'", path, line);
      }
      if (p.name.empty()) throw ParseError("property without a name", path, line);
      h.elements.back().props.push_back(p);
    } else if (kw == "end_header") {
      if (!have_format) throw ParseError("PLY header has no format line", path, line);
      h.body_offset = std::min(pos, data.size());
      h.body_line = line + 1;
      return h;
    } else {
      throw ParseError("unexpected PLY header line '" + quote_input(text) + "'", path, line);
    }
  }
}

// Reads scalar values from the body, as double (exact for every PLY integer type).
class BodyReader {
 public:
  BodyReader(const std::string& data, const Header& h, const std::string& path)
      : m_data(data), m_pos(h.body_offset), m_line(h.body_line), m_format(h.format), m_path(path) {}

  double read(PlyType t) {
    return m_format == Format::ascii ? read_ascii(t) : read_binary(t);
  }
  size_t remaining() const { return m_data.size() - m_pos; }
  [[noreturn]] void fail(const std::string& msg) const {
    if (m_format == Format::ascii) throw ParseError(msg, m_path, m_line);
    throw ParseError(msg + " (at byte " + std::to_string(m_pos) + ")", m_path);
  }

 private:
  double read_ascii(PlyType t) {
    while (m_pos < m_data.size() && std::isspace(static_cast<unsigned char>(m_data[m_pos]))) {
      if (m_data[m_pos] == '\n') ++m_line;
      ++m_pos;
    }
    if (m_pos >= m_data.size()) fail("unexpected end of file in PLY data");
    size_t end = m_pos;
    while (end < m_data.size() && !std::isspace(static_cast<unsigned char>(m_data[end]))) ++end;
    const std::string tok = m_data.substr(m_pos, end - m_pos);
    char* stop = nullptr;
    const double v = std::strtod(tok.c_str(), &stop);
    if (*stop != '\0') fail("expected a number, got '" + quote_input(tok) + "'");
    if (is_integer(t) && v != std::floor(v)) fail("expected an integer, got '" + quote_input(tok) + "'");
    m_pos = end;
    return v;
  }

  double read_binary(PlyType t) {
    const size_t n = type_size(t);
    if (m_pos + n > m_data.size()) fail("unexpected end of file in PLY data");
    unsigned char b[8];
    std::memcpy(b, m_data.data() + m_pos, n);
    m_pos += n;
    const bool file_le = m_format == Format::binary_le;
    if (file_le != (std::endian::native == std::endian::little))
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case PlyType::i8: { int8_t v; std::memcpy(&v, b, 1); return v; }
      case PlyType::u8: { uint8_t v; std::memcpy(&v, b, 1); return v; }
      case PlyType::i16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::u16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::i32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::u32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f32: { float v; std::memcpy(&v, b, 4); return double(v); }
      case PlyType::f64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

  const std::string& m_data;
  size_t m_pos;
  int m_line;
  Format m_format;
  const std::string& m_path;
};

int find_prop(const Element& e, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (size_t i = 0; i < e.props.size(); ++i)
      if (!e.props[i].is_list && e.props[i].name == n) return int(i);
  return -1;
}

}  // namespace

std::unique_ptr<TriangleMesh> load_ply(const std::string& path) {
  const std::string data = core::read_file(path, "mesh file");
  const Header h = parse_header(data, path);
  BodyReader body(data, h, path);

  auto mesh = std::make_unique<TriangleMesh>();
  mesh->name = path;
  bool have_vertices = false, have_faces = false;
  for (const Element& e : h.elements) {
    // Each instance takes at least one byte per property (binary) or two (ascii): a
    // cheap guard against corrupt counts before reserving memory.
    if (!e.props.empty() && e.count > body.remaining() / e.props.size())
      body.fail("element '" + quote_input(e.name) + "' declares " + std::to_string(e.count) + " entries, more than the file holds");
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1, ilist = -1;
    if (is_vertex) {
      if (have_vertices) body.fail("more than one 'vertex' element");
      have_vertices = true;
      ix = find_prop(e, {"x"}), iy = find_prop(e, {"y"}), iz = find_prop(e, {"z"});
      if (ix < 0 || iy < 0 || iz < 0) throw ParseError("PLY vertex element lacks x, y or z", path);
      inx = find_prop(e, {"nx"}), iny = find_prop(e, {"ny"}), inz = find_prop(e, {"nz"});
      if (inx < 0 || iny < 0 || inz < 0) inx = iny = inz = -1;
      iu = find_prop(e, {"u", "s", "texture_u", "texture_s"});
      iv = find_prop(e, {"v", "t", "texture_v", "texture_t"});
      if (iu < 0 || iv < 0) iu = iv = -1;
      mesh->positions.reserve(e.count);
      if (inx >= 0) mesh->normals.reserve(e.count);
      if (iu >= 0) mesh->uvs.reserve(e.count);
    } else if (is_face) {
      if (have_faces) body.fail("more than one 'face' element");
      have_faces = true;
      for (size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].is_list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          ilist = int(i);
      if (ilist < 0) throw ParseError("PLY face element has no vertex_indices list", path);
      if (!is_integer(e.props[size_t(ilist)].type)) throw ParseError("PLY face indices must be integers", path);
      mesh->triangles.reserve(e.count);
    }
    std::vector<double> vals(e.props.size());
    std::vector<uint32_t> poly;
    for (size_t k = 0; k < e.count; ++k) {
      for (size_t p = 0; p < e.props.size(); ++p) {
        const Property& prop = e.props[p];
        if (!prop.is_list) {
          vals[p] = body.read(prop.type);
          continue;
        }
        const double n = body.read(prop.count_type);
        // A list length is a whole number a reader can loop over: NaN, a fraction or
        // 1e47 (the fuzzer's ASCII count) must not reach size_t(n).
        if (!(n >= 0) || n != std::floor(n) || n > 16777216.0)
          body.fail("bad list length in element '" + quote_input(e.name) + "' (a whole number in 0 .. 2^24)");
        const bool indices = int(p) == ilist;
        if (indices) {
          if (n < 3) body.fail("face " + std::to_string(k) + " has " + std::to_string(int(n)) + " vertices (at least 3 needed)");
          poly.clear();
        }
        for (size_t j = 0; j < size_t(n); ++j) {
          const double v = body.read(prop.type);
          if (indices) {
            if (v < 0 || v > 4294967295.0) body.fail("face " + std::to_string(k) + ": vertex index out of range");
            poly.push_back(uint32_t(v));
          }
        }
        if (indices)
          for (size_t j = 1; j + 1 < poly.size(); ++j) mesh->triangles.push_back({poly[0], poly[j], poly[j + 1]});
      }
      if (is_vertex) {
        mesh->positions.emplace_back(float(vals[size_t(ix)]), float(vals[size_t(iy)]), float(vals[size_t(iz)]));
        if (inx >= 0)
          mesh->normals.emplace_back(float(vals[size_t(inx)]), float(vals[size_t(iny)]), float(vals[size_t(inz)]));
        if (iu >= 0) mesh->uvs.emplace_back(float(vals[size_t(iu)]), float(vals[size_t(iv)]));
      }
    }
  }
  if (!have_vertices) throw ParseError("PLY file has no vertex element", path);
  if (!have_faces || mesh->triangles.empty()) throw ParseError("PLY file has no faces", path);
  const size_t nv = mesh->positions.size();
  for (const auto& tri : mesh->triangles)
    for (uint32_t i : tri)
      if (i >= nv)
        throw ParseError("face vertex index " + std::to_string(i) + " out of range (" + std::to_string(nv) +
                             " vertices)", path);
  for (Vec3& n : mesh->normals) n.normalize();
  return mesh;
}

}  // namespace dp::scene
