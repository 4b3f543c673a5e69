// Lossless EXR files of raw accumulation buffers (core/raw_image.h), written by
// `deltapath render --partial` and read by `deltapath merge` (issue 17). Every value is
// kept bit for bit: a double sum channel is stored as two EXR UINT channels holding the
// high and low 32 bits of its IEEE-754 pattern, "<sum>.R.hi", "<sum>.R.lo", ... for R, G,
// B; a count (int64) likewise as "<count>.n.hi", "<count>.n.lo". String facts about the
// render go into the header as string attributes "deltapath.<key>". Viewers show these
// files as integer noise: they are for merging, not for looking at.
// Errors throw dp::IoError naming the file (unreadable, not such a file, a channel missing
// or of the wrong type).
#pragma once

#include <map>
#include <string>

#include "core/raw_image.h"

namespace dp::core {

using Facts = std::map<std::string, std::string>;  // key (without "deltapath.") -> value

void write_raw_exr(const std::string& path, const RawImage& raw, const Facts& facts);
// Reads the buffers and every "deltapath.*" string attribute into `facts`. Throws if the
// file has no "deltapath.*" attribute or no raw channel. With pixels = false only the
// header is read: the result has the size but no buffers (a merge checks every file's
// facts before it reads any file's pixels, then holds one file at a time).
RawImage read_raw_exr(const std::string& path, Facts& facts, bool pixels = true);

}  // namespace dp::core
