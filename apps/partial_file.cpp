#include "apps/partial_file.h"

#include <cstdio>
#include <cstdint>
#include <cstdlib>

#include "core/error.h"
#include "core/read_file.h"

#ifndef DP_VERSION
#define DP_VERSION "unknown"
#endif

namespace dp::apps {

namespace {
const char* const kPerPartFacts[] = {"scene",   "interrupted", "wall_seconds", "passes",
                                     "threads", "part",        "time_budget"};

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

int64_t integer_fact(const PartialFile& f, const std::string& key, int64_t lo, int64_t hi) {
  const auto it = f.facts.find(key);
  if (it == f.facts.end()) throw ValueError("not a complete --partial file: fact '" + key + "' is missing", f.path);
  const std::string& v = it->second;
  char* end = nullptr;
  const long long x = v.empty() ? 0 : std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0' || x < lo || x > hi)
    throw ValueError("fact '" + key + "' is '" + quote_input(v, 40) + "', not an integer in [" + std::to_string(lo) +
                         ", " + std::to_string(hi) + "]",
                     f.path);
  return x;
}

std::string deltapath_version() { return DP_VERSION; }

std::string scene_hash(const std::string& scene_path) {
  const std::string bytes = core::read_file(scene_path, "cannot read the scene");
  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64 offset basis and prime
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

bool is_per_part_fact(const std::string& key) {
  for (const char* k : kPerPartFacts)
    if (key == k) return true;
  return starts_with(key, "counter.");
}

void write_partial(const std::string& path, const core::RawImage& raw, const core::Facts& facts) {
  core::Facts all = facts;
  all["format"] = kPartialFormat;
  all["version"] = deltapath_version();
  core::write_raw_exr(path, raw, all);
}

PartialFile read_partial(const std::string& path, bool pixels) {
  core::check_readable_file(path, "cannot read the partial file");
  PartialFile f;
  f.path = path;
  f.raw = core::read_raw_exr(path, f.facts, pixels);
  const auto format = f.facts.find("format");
  if (format == f.facts.end() || format->second != kPartialFormat)
    throw ValueError("format is '" + (format == f.facts.end() ? std::string("none") : quote_input(format->second, 40)) +
                         "', this deltapath reads '" + kPartialFormat + "'",
                     path);
  for (const char* key : {"integrator", "scene", "scene_hash", "interrupted", "wall_seconds"})
    if (!f.facts.count(key))
      throw ValueError(std::string("not a complete --partial file: fact '") + key + "' is missing", path);
  integer_fact(f, "seed", INT64_MIN, INT64_MAX);  // --seed (uint64) written as int64, as in sidecars
  integer_fact(f, "passes", 0, INT64_MAX);
  for (const auto& [key, v] : f.facts)
    if (starts_with(key, "counter.")) integer_fact(f, key, INT64_MIN, INT64_MAX);
  f.parts = int(integer_fact(f, "parts", 1, 1 << 20));
  f.part = int(integer_fact(f, "part", 1, f.parts));
  if (integer_fact(f, "width", 1, 1 << 30) != f.raw.width || integer_fact(f, "height", 1, 1 << 30) != f.raw.height)
    throw ValueError("facts width/height do not match the image size", path);
  integer_fact(f, "spp", 0, 1 << 30);  // 0: a --time render
  integer_fact(f, "max_depth", 1, 1024);
  return f;
}

std::string first_difference(const PartialFile& a, const PartialFile& b) {
  auto value = [](const core::Facts& facts, const std::string& key) {
    const auto it = facts.find(key);
    return it == facts.end() ? std::string("(none)") : quote_input(it->second, 60);
  };
  auto compare = [&](const core::Facts& keys) -> std::string {
    for (const auto& [key, v] : keys) {
      if (is_per_part_fact(key)) continue;
      const std::string va = value(a.facts, key), vb = value(b.facts, key);
      if (va != vb) return key + " differs (" + a.path + ": " + va + ", " + b.path + ": " + vb + ")";
    }
    return {};
  };
  std::string d = compare(a.facts);
  if (d.empty()) d = compare(b.facts);  // keys only b has
  const bool buffers = !a.raw.sums.empty() && !b.raw.sums.empty();
  if (d.empty() && buffers) {
    const std::string layout = a.raw.layout_difference(b.raw);
    if (!layout.empty()) d = "buffers differ: " + layout;
  }
  return d;
}

core::Json settings_json(const core::Facts& facts) {
  core::Json j = core::Json::object();
  for (const auto& [key, v] : facts)
    if (starts_with(key, "setting.")) j[key.substr(8)] = v;
  return j;
}

}  // namespace dp::apps
