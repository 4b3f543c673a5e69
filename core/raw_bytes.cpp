#include "core/raw_bytes.h"

#include <cstring>

#include "core/error.h"

namespace dp::core {

namespace {
constexpr uint64_t kMagic = 0x3142'5741'5250'44ull;  // "DPRAWB1"

struct Writer {
  std::vector<uint8_t> out;
  void put(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  }
  void u64(uint64_t v) { put(&v, sizeof v); }
  void str(const std::string& s) {
    u64(s.size());
    put(s.data(), s.size());
  }
};

struct Reader {
  const std::vector<uint8_t>& in;
  size_t at = 0;
  void get(void* p, size_t n) {
    if (n > in.size() - at) throw ValueError("raw bytes: truncated at byte " + std::to_string(at));
    std::memcpy(p, in.data() + at, n);
    at += n;
  }
  uint64_t u64() {
    uint64_t v = 0;
    get(&v, sizeof v);
    return v;
  }
  std::string str() {
    const uint64_t n = u64();
    if (n > in.size() - at) throw ValueError("raw bytes: truncated string at byte " + std::to_string(at));
    std::string s(reinterpret_cast<const char*>(in.data() + at), size_t(n));
    at += size_t(n);
    return s;
  }
};

template <class T>
void put_buffers(Writer& w, const std::map<std::string, std::vector<T>>& m) {
  w.u64(m.size());
  for (const auto& [name, v] : m) {
    w.str(name);
    w.u64(v.size());
    w.put(v.data(), v.size() * sizeof(T));
  }
}

template <class T>
void get_buffers(Reader& r, std::map<std::string, std::vector<T>>& m, size_t pixels) {
  const uint64_t n = r.u64();
  for (uint64_t i = 0; i < n; ++i) {
    const std::string name = r.str();
    if (r.u64() != pixels) throw ValueError("raw bytes: buffer '" + name + "' does not match the image size");
    if (pixels * sizeof(T) > r.in.size() - r.at) throw ValueError("raw bytes: buffer '" + name + "' truncated");
    std::vector<T>& v = m[name];
    v.resize(pixels);
    r.get(v.data(), pixels * sizeof(T));
  }
}
}  // namespace

std::vector<uint8_t> raw_to_bytes(const RawImage& raw, const std::map<std::string, std::string>& facts) {
  Writer w;
  w.u64(kMagic);
  w.u64(uint64_t(raw.width));
  w.u64(uint64_t(raw.height));
  w.u64(facts.size());
  for (const auto& [k, v] : facts) {
    w.str(k);
    w.str(v);
  }
  put_buffers(w, raw.sums);
  put_buffers(w, raw.counts);
  return std::move(w.out);
}

RawImage raw_from_bytes(const std::vector<uint8_t>& bytes, std::map<std::string, std::string>& facts) {
  Reader r{bytes};
  if (bytes.size() < 8 || r.u64() != kMagic) throw ValueError("raw bytes: not a Deltapath raw image");
  RawImage raw;
  const uint64_t w = r.u64(), h = r.u64();
  if (w > (1u << 20) || h > (1u << 20)) throw ValueError("raw bytes: implausible size");
  raw.width = int(w);
  raw.height = int(h);
  facts.clear();
  const uint64_t n = r.u64();
  for (uint64_t i = 0; i < n; ++i) {
    std::string k = r.str();
    facts[k] = r.str();
  }
  get_buffers(r, raw.sums, raw.pixels());
  get_buffers(r, raw.counts, raw.pixels());
  if (r.at != bytes.size()) throw ValueError("raw bytes: trailing data");
  return raw;
}

}  // namespace dp::core
