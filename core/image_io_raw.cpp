// OpenEXR side of core/image_io_raw.h (only image_io*.cpp include OpenEXR).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <cstring>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io_raw.h"

namespace dp::core {

namespace {
constexpr const char* kPrefix = "deltapath.";
constexpr const char* kComps[3] = {"R", "G", "B"};

// One double (or int64) channel as two 32-bit words.
struct Words {
  std::vector<uint32_t> hi, lo;
  explicit Words(size_t n) : hi(n), lo(n) {}
  void set(size_t i, uint64_t bits) {
    hi[i] = uint32_t(bits >> 32);
    lo[i] = uint32_t(bits & 0xffffffffu);
  }
  uint64_t get(size_t i) const { return (uint64_t(hi[i]) << 32) | lo[i]; }
};

uint64_t bits_of(double d) {
  uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}
double double_of(uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}

void bind_words(Imf::FrameBuffer& fb, const std::string& name, Words& w, int width, int x0, int y0) {
  // OpenEXR addresses pixel (x, y) as base + x * xStride + y * yStride (data window origin).
  const size_t origin = (size_t(x0) + size_t(y0) * size_t(width)) * sizeof(uint32_t);
  for (auto* v : {&w.hi, &w.lo})
    fb.insert(name + (v == &w.hi ? ".hi" : ".lo"),
              Imf::Slice(Imf::UINT, reinterpret_cast<char*>(v->data()) - origin, sizeof(uint32_t),
                         sizeof(uint32_t) * size_t(width)));
}

// "<base>.hi" -> base for every UINT channel; throws on another type or a missing ".lo".
std::vector<std::string> word_channels(const Imf::Header& header, const std::string& path) {
  std::vector<std::string> bases;
  const Imf::ChannelList& channels = header.channels();
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    const std::string name = it.name();
    if (it.channel().type != Imf::UINT)
      throw IoError("channel '" + name + "' is not UINT: not a --partial file of deltapath", path);
    if (name.size() > 3 && name.compare(name.size() - 3, 3, ".hi") == 0) {
      const std::string base = name.substr(0, name.size() - 3);
      if (!channels.findChannel(base + ".lo")) throw IoError("channel '" + base + ".lo' is missing", path);
      bases.push_back(base);
    }
  }
  return bases;
}
}  // namespace

void write_raw_exr(const std::string& path, const RawImage& raw, const Facts& facts) {
  const size_t n = raw.pixels();
  if (n == 0) throw IoError("no pixels to write", path);
  try {
    Imf::Header header(raw.width, raw.height);
    for (const auto& [k, v] : facts) header.insert(kPrefix + k, Imf::StringAttribute(v));
    Imf::FrameBuffer fb;
    std::vector<Words> words;
    words.reserve(raw.sums.size() * 3 + raw.counts.size());
    std::vector<std::string> names;
    for (const auto& [name, v] : raw.sums) {
      if (v.size() != n) throw IoError("sum '" + name + "' has the wrong size", path);
      for (int c = 0; c < 3; ++c) {
        words.emplace_back(n);
        for (size_t i = 0; i < n; ++i) words.back().set(i, bits_of(v[i][c]));
        names.push_back(name + "." + kComps[c]);
      }
    }
    for (const auto& [name, v] : raw.counts) {
      if (v.size() != n) throw IoError("count '" + name + "' has the wrong size", path);
      words.emplace_back(n);
      for (size_t i = 0; i < n; ++i) words.back().set(i, uint64_t(v[i]));
      names.push_back(name + ".n");
    }
    for (size_t w = 0; w < words.size(); ++w) {
      header.channels().insert(names[w] + ".hi", Imf::Channel(Imf::UINT));
      header.channels().insert(names[w] + ".lo", Imf::Channel(Imf::UINT));
      bind_words(fb, names[w], words[w], raw.width, 0, 0);
    }
    write_atomically(path, [&](const std::string& tmp) {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(raw.height);
    });
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(std::string("cannot write EXR: ") + e.what(), path);
  }
}

RawImage read_raw_exr(const std::string& path, Facts& facts, bool pixels) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    facts.clear();
    const std::string prefix = kPrefix;
    for (auto it = header.begin(); it != header.end(); ++it) {
      const std::string name = it.name();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute());
      if (!s) throw IoError("header attribute '" + name + "' is not a string", path);
      facts[name.substr(prefix.size())] = s->value();
    }
    if (facts.empty()) throw IoError("not a --partial file of deltapath (no deltapath.* header attributes)", path);
    const Imath::Box2i dw = header.dataWindow();
    RawImage raw;
    raw.width = dw.max.x - dw.min.x + 1;
    raw.height = dw.max.y - dw.min.y + 1;
    const size_t n = raw.pixels();
    if (!pixels) return raw;
    // Every channel base is "<sum>.R|G|B" or "<count>.n".
    std::map<std::string, Words> words;
    Imf::FrameBuffer fb;
    for (const std::string& base : word_channels(header, path)) {
      const size_t dot = base.rfind('.');
      const std::string comp = dot == std::string::npos ? "" : base.substr(dot + 1);
      if (comp != "R" && comp != "G" && comp != "B" && comp != "n")
        throw IoError("unexpected channel '" + base + ".hi' in a --partial file", path);
      auto& w = words.emplace(base, Words(n)).first->second;
      bind_words(fb, base, w, raw.width, dw.min.x, dw.min.y);
    }
    if (words.empty()) throw IoError("no raw buffer channels in a --partial file", path);
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (const auto& [base, w] : words) {
      const size_t dot = base.rfind('.');
      const std::string name = base.substr(0, dot), comp = base.substr(dot + 1);
      if (comp == "n") {
        auto& v = raw.counts[name];
        v.resize(n);
        for (size_t i = 0; i < n; ++i) v[i] = int64_t(w.get(i));
        continue;
      }
      for (const char* c : kComps)
        if (!words.count(name + "." + c)) throw IoError("sum '" + name + "' lacks channel " + c, path);
      auto& v = raw.sums[name];
      if (v.empty()) v.assign(n, Rgbd::Zero());
      const int c = comp == "R" ? 0 : comp == "G" ? 1 : 2;
      for (size_t i = 0; i < n; ++i) v[i][c] = double_of(w.get(i));
    }
    return raw;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(std::string("cannot read EXR: ") + e.what(), path);
  }
}

}  // namespace dp::core
