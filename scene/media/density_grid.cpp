#include "scene/media/density_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace dp::scene {

namespace {
constexpr int64_t kMaxNodes = int64_t(1) << 28;  // 1 GiB of floats

template <class T>
T read_le(std::ifstream& in, const std::string& path, const char* what) {
  T v{};
  in.read(reinterpret_cast<char*>(&v), sizeof(T));
  if (!in) throw IoError(std::string("truncated .vol file: could not read the ") + what, path);
  return v;  // the build targets are little-endian (x86-64, aarch64)
}
}  // namespace

float DensityGrid::lookup(const Vec3& p) const {
  const Vec3 u = (p - lo).cwiseQuotient(hi - lo);
  if (!(u.minCoeff() >= 0.0f && u.maxCoeff() <= 1.0f)) return 0.0f;
  const float fx = u.x() * float(nx - 1), fy = u.y() * float(ny - 1), fz = u.z() * float(nz - 1);
  const int x0 = std::min(int(fx), nx - 2 < 0 ? 0 : nx - 2), y0 = std::min(int(fy), ny - 2 < 0 ? 0 : ny - 2),
            z0 = std::min(int(fz), nz - 2 < 0 ? 0 : nz - 2);
  const int x1 = std::min(x0 + 1, nx - 1), y1 = std::min(y0 + 1, ny - 1), z1 = std::min(z0 + 1, nz - 1);
  const float tx = std::clamp(fx - float(x0), 0.0f, 1.0f), ty = std::clamp(fy - float(y0), 0.0f, 1.0f),
              tz = std::clamp(fz - float(z0), 0.0f, 1.0f);
  auto at = [&](int x, int y, int z) { return values[(size_t(z) * size_t(ny) + size_t(y)) * size_t(nx) + size_t(x)]; };
  const float c00 = at(x0, y0, z0) * (1 - tx) + at(x1, y0, z0) * tx, c10 = at(x0, y1, z0) * (1 - tx) + at(x1, y1, z0) * tx;
  const float c01 = at(x0, y0, z1) * (1 - tx) + at(x1, y0, z1) * tx, c11 = at(x0, y1, z1) * (1 - tx) + at(x1, y1, z1) * tx;
  return (c00 * (1 - ty) + c10 * ty) * (1 - tz) + (c01 * (1 - ty) + c11 * ty) * tz;
}

bool DensityGrid::clip(const Vec3& o, const Vec3& d, float t_max, float& t0, float& t1) const {
  t0 = 0.0f;
  t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / d[a];
    float ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    if (std::isnan(ta) || std::isnan(tb)) {  // parallel to the slab: inside or not at all
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0;
}

void DensityGrid::finalize(const std::string& where) {
  if (nx < 1 || ny < 1 || nz < 1 || int64_t(nx) * ny * nz > kMaxNodes)
    throw ParseError("density grid size " + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) +
                         " out of range (1 .. 2^28 nodes)",
                     where);
  if (values.size() != size_t(nx) * size_t(ny) * size_t(nz)) throw ParseError("density grid: wrong number of values", where);
  if (!is_finite(lo) || !is_finite(hi) || !((hi - lo).minCoeff() > 0.0f))
    throw ParseError("density grid bounds must be finite with hi > lo on every axis", where);
  max_value = 0.0f;
  min_value = kInfinity;
  for (float v : values) {
    if (!(v >= 0.0f) || !std::isfinite(v)) throw ParseError("density grid values must be finite and >= 0", where);
    max_value = std::max(max_value, v);
    min_value = std::min(min_value, v);
  }
}

DensityGrid read_vol_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open the density grid file", path);
  char magic[4] = {};
  in.read(magic, 4);
  if (!in || std::memcmp(magic, "VOL", 3) != 0) throw ParseError("not a .vol file (no 'VOL' header)", path);
  if (magic[3] != 3) throw ParseError(".vol version " + std::to_string(int(magic[3])) + " (only version 3)", path);
  if (read_le<int32_t>(in, path, "encoding") != 1) throw ParseError(".vol encoding is not float32 (1)", path);
  DensityGrid g;
  g.nx = read_le<int32_t>(in, path, "size");
  g.ny = read_le<int32_t>(in, path, "size");
  g.nz = read_le<int32_t>(in, path, "size");
  const int32_t channels = read_le<int32_t>(in, path, "channel count");
  if (channels != 1) throw ParseError(".vol has " + std::to_string(channels) + " channels (a density grid has 1)", path);
  float b[6];
  for (float& v : b) v = read_le<float>(in, path, "bounds");
  g.lo = Vec3(b[0], b[1], b[2]);
  g.hi = Vec3(b[3], b[4], b[5]);
  if (g.nx < 1 || g.ny < 1 || g.nz < 1 || int64_t(g.nx) * g.ny * g.nz > kMaxNodes) g.finalize(path);  // the size error
  g.values.resize(size_t(g.nx) * size_t(g.ny) * size_t(g.nz));
  in.read(reinterpret_cast<char*>(g.values.data()), std::streamsize(g.values.size() * sizeof(float)));
  if (!in) throw IoError("truncated .vol file: fewer values than " + std::to_string(g.values.size()), path);
  g.finalize(path);
  return g;
}

void write_vol_file(const std::string& path, const DensityGrid& g) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError("cannot write the density grid file", path);
  auto put = [&](const auto& v) { out.write(reinterpret_cast<const char*>(&v), sizeof(v)); };
  out.write("VOL\x03", 4);
  put(int32_t(1));
  put(int32_t(g.nx));
  put(int32_t(g.ny));
  put(int32_t(g.nz));
  put(int32_t(1));
  for (int a = 0; a < 3; ++a) put(g.lo[a]);
  for (int a = 0; a < 3; ++a) put(g.hi[a]);
  out.write(reinterpret_cast<const char*>(g.values.data()), std::streamsize(g.values.size() * sizeof(float)));
  if (!out) throw IoError("could not write the density grid file", path);
}

}  // namespace dp::scene
