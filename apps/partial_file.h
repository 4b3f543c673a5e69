// `render --partial` files (issue 17): one EXR holding a render's raw sums and sample
// counts bit for bit (core/image_io_raw.h) plus, as EXR header string attributes
// "deltapath.<key>", the facts `merge` needs to combine files:
//   format         kPartialFormat (the layout of this file)
//   version        deltapath version that wrote it
//   integrator     name; setting.<key>: every resolved integrator setting
//   seed, spp (0 for a --time render), max_depth, width, height
//   scene_hash     FNV-1a 64 of the scene file's bytes (files it references are not hashed)
//   part, parts    this file is part K of N (1-based; 1/1 without --part)
// and per-part facts that may differ between the parts of one render (kPerPartFacts):
//   scene (the path as given), interrupted, wall_seconds, passes, threads, time_budget
//   (a --time render's seconds), counter.<name>.
// Two files hold parts of the same render iff every other fact is equal.
#pragma once

#include <string>

#include "core/image_io_raw.h"
#include "core/json.h"

namespace dp::apps {

constexpr const char* kPartialFormat = "deltapath-partial-1";

struct PartialFile {
  std::string path;
  core::Facts facts;
  core::RawImage raw;
  int part = 1, parts = 1;  // 1-based
};

// Hex FNV-1a 64 of the file's bytes; throws IoError naming the file.
std::string scene_hash(const std::string& scene_path);
// The version string of this build.
std::string deltapath_version();

void write_partial(const std::string& path, const core::RawImage& raw, const core::Facts& facts);
// Reads and validates a --partial file (format, integer facts, size); IoError/ValueError
// naming the file. With pixels = false only its header (raw has the size, no buffers).
PartialFile read_partial(const std::string& path, bool pixels = true);
// The fact `key` as an integer in [lo, hi]; ValueError naming the file otherwise
// (read_partial has checked spp, max_depth, seed, passes, width, height, counter.*).
int64_t integer_fact(const PartialFile& f, const std::string& key, int64_t lo, int64_t hi);
// Empty if `a` and `b` may be merged as parts of one render, otherwise the first fact
// that differs, as "<key> differs (A: <value>, B: <value>)" with the two file names, or
// how their buffers differ (when both hold buffers).
std::string first_difference(const PartialFile& a, const PartialFile& b);
// Whether `key` is a per-part fact (not compared by first_difference).
bool is_per_part_fact(const std::string& key);
// The settings facts as a JSON object, for sidecars.
core::Json settings_json(const core::Facts& facts);

}  // namespace dp::apps
