// Reader for Mitsuba's .serialized meshes (format in mitsuba_serialized.h).
#include "scene/loaders/mitsuba/mitsuba_serialized.h"

#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/error.h"
#include "core/read_file.h"

namespace dp::scene {

namespace {

constexpr uint16_t kMagic = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColors = 0x0008, kFaceNormals = 0x0010,
                   kSingle = 0x1000, kDouble = 0x2000;

template <typename T>
T read_le(const unsigned char* p) {
  T v = 0;
  for (size_t i = 0; i < sizeof(T); ++i) v |= T(T(p[i]) << (8 * i));
  return v;
}

// Sequential reads from a zlib stream held in memory.
class Inflater {
 public:
  Inflater(const std::vector<unsigned char>& data, size_t offset, const std::string& path) : m_path(path) {
    std::memset(&m_z, 0, sizeof(m_z));
    m_z.next_in = const_cast<Bytef*>(data.data() + offset);
    m_z.avail_in = uInt(data.size() - offset);
    if (inflateInit(&m_z) != Z_OK) throw IoError("cannot initialise zlib", path);
  }
  ~Inflater() { inflateEnd(&m_z); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  void read(void* dst, size_t bytes) {
    auto* out = static_cast<Bytef*>(dst);
    while (bytes > 0) {
      const uInt chunk = uInt(std::min<size_t>(bytes, 1u << 30));
      m_z.next_out = out;
      m_z.avail_out = chunk;
      while (m_z.avail_out > 0) {
        const int rc = inflate(&m_z, Z_NO_FLUSH);
        if (rc == Z_STREAM_END && m_z.avail_out > 0) fail("compressed mesh data ends early");
        if (rc != Z_OK && rc != Z_STREAM_END) fail(std::string("corrupt compressed data (zlib: ") + (m_z.msg ? m_z.msg : "error") + ")");
        if (rc == Z_STREAM_END) break;
      }
      out += chunk;
      bytes -= chunk;
    }
  }
  template <typename T>
  T value() {
    unsigned char b[sizeof(T)];
    read(b, sizeof(T));
    return read_le<T>(b);
  }
  // n values stored as float or double, converted to float.
  std::vector<float> reals(size_t n, bool dbl) {
    std::vector<float> out(n);
    if (!dbl) {
      std::vector<unsigned char> raw(n * 4);
      read(raw.data(), raw.size());
      for (size_t i = 0; i < n; ++i) {
        const uint32_t bits = read_le<uint32_t>(&raw[4 * i]);
        std::memcpy(&out[i], &bits, 4);
      }
    } else {
      std::vector<unsigned char> raw(n * 8);
      read(raw.data(), raw.size());
      for (size_t i = 0; i < n; ++i) {
        const uint64_t bits = read_le<uint64_t>(&raw[8 * i]);
        double d;
        std::memcpy(&d, &bits, 8);
        out[i] = float(d);
      }
    }
    return out;
  }
  [[noreturn]] void fail(const std::string& msg) const { throw ParseError("serialized mesh: " + msg, m_path); }

 private:
  z_stream m_z;
  std::string m_path;
};

}  // namespace

SerializedMesh load_serialized(const std::string& path, int shape_index) {
  core::check_readable_file(path, "serialized mesh");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open serialized mesh", path);
  const std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError("cannot read serialized mesh", path);
  auto fail = [&](const std::string& msg) -> void { throw ParseError("serialized mesh: " + msg, path); };
  if (data.size() < 8) fail("file too short");
  if (read_le<uint16_t>(&data[0]) != kMagic) fail("not a Mitsuba .serialized file (bad magic number)");
  const uint16_t version = read_le<uint16_t>(&data[2]);
  if (version != 3 && version != 4) fail("unsupported format version " + std::to_string(version) + " (3 or 4)");
  if (shape_index < 0) fail("shape_index must be >= 0");

  size_t offset = 0;
  if (shape_index > 0) {
    const uint32_t count = read_le<uint32_t>(&data[data.size() - 4]);
    if (uint32_t(shape_index) >= count)
      fail("shape_index " + std::to_string(shape_index) + " out of range (the file holds " + std::to_string(count) +
           " meshes)");
    const size_t entry = version == 4 ? 8 : 4;
    if (data.size() < 4 + size_t(count) * entry) fail("truncated end-of-file dictionary");
    const size_t at = data.size() - 4 - (size_t(count) - size_t(shape_index)) * entry;
    offset = version == 4 ? size_t(read_le<uint64_t>(&data[at])) : size_t(read_le<uint32_t>(&data[at]));
    if (offset + 4 >= data.size()) fail("mesh offset beyond the end of the file");
    if (read_le<uint16_t>(&data[offset]) != kMagic || read_le<uint16_t>(&data[offset + 2]) != version)
      fail("mesh " + std::to_string(shape_index) + " has a bad header");
  }

  Inflater z(data, offset + 4, path);
  const uint32_t flags = z.value<uint32_t>();
  if ((flags & kSingle) && (flags & kDouble)) fail("both single and double precision flags are set");
  const bool dbl = (flags & kDouble) != 0;
  std::string name;
  if (version == 4)
    for (char c = char(z.value<uint8_t>()); c != 0; c = char(z.value<uint8_t>())) name += c;
  const uint64_t nv = z.value<uint64_t>(), nt = z.value<uint64_t>();
  // 2^31 vertices / triangles: far beyond any mesh this renderer can hold in memory.
  if (nv == 0 || nt == 0 || nv > (uint64_t(1) << 31) || nt > (uint64_t(1) << 31))
    fail("implausible vertex/triangle counts " + std::to_string(nv) + "/" + std::to_string(nt));

  SerializedMesh out;
  out.mesh = std::make_unique<TriangleMesh>();
  TriangleMesh& m = *out.mesh;
  m.name = name.empty() ? path + "@" + std::to_string(shape_index) : name;
  const std::vector<float> p = z.reals(3 * nv, dbl);
  m.positions.resize(nv);
  for (size_t i = 0; i < nv; ++i) m.positions[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  if (flags & kHasNormals) {
    const std::vector<float> n = z.reals(3 * nv, dbl);
    m.normals.resize(nv);
    for (size_t i = 0; i < nv; ++i) m.normals[i] = Vec3(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
  }
  if (flags & kHasTexcoords) {
    const std::vector<float> t = z.reals(2 * nv, dbl);
    m.uvs.resize(nv);
    for (size_t i = 0; i < nv; ++i) m.uvs[i] = Vec2(t[2 * i], t[2 * i + 1]);
  }
  if (flags & kHasColors) (void)z.reals(3 * nv, dbl);
  std::vector<unsigned char> idx(size_t(nt) * 12);
  z.read(idx.data(), idx.size());
  m.triangles.resize(nt);
  for (size_t i = 0; i < nt; ++i)
    for (int j = 0; j < 3; ++j) {
      const uint32_t v = read_le<uint32_t>(&idx[12 * i + 4 * size_t(j)]);
      if (v >= nv) fail("triangle " + std::to_string(i) + " references vertex " + std::to_string(v) + " of " + std::to_string(nv));
      m.triangles[i][size_t(j)] = v;
    }
  out.face_normals = (flags & kFaceNormals) != 0;
  return out;
}

}  // namespace dp::scene
