// A RawImage (core/raw_image.h) and its facts as one byte string, for sending a render's
// share between processes (`render --mpi`, issue 17). Lossless (doubles and counts as
// stored, host byte order: both ends run the same build on the same kind of machine).
// Layout: magic, width, height, then the facts, sums and counts as length-prefixed
// (u64) names and values.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/raw_image.h"

namespace dp::core {

std::vector<uint8_t> raw_to_bytes(const RawImage& raw, const std::map<std::string, std::string>& facts);
// Throws dp::ValueError ("raw bytes: ...") on a truncated or foreign byte string.
RawImage raw_from_bytes(const std::vector<uint8_t>& bytes, std::map<std::string, std::string>& facts);

}  // namespace dp::core
