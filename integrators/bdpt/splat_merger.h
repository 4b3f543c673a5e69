// Deterministic accumulation of light-tracing splats: each (pass, tile) hands in its
// splat list; lists are added to the shared image in tile-index order within a pass and
// pass after pass, whatever thread rendered them and when, so the image is bit-identical
// for any thread count. A list is merged as soon as every lower tile of its pass is in
// (memory stays at about one list per thread); finish_pass() merges the rest (a stopped
// pass leaves gaps) and starts the next pass. Thread-safe.
#pragma once

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <vector>

#include "core/math.h"

namespace dp::integrators {

struct Splat {
  int32_t pixel = 0;  // y * width + x
  Rgb value = Rgb::Zero();
};

class SplatMerger {
 public:
  SplatMerger(size_t tiles, std::vector<Rgbd>& image) : m_pending(tiles), m_ready(tiles, 0), m_image(image) {}
  void submit(int tile, std::vector<Splat>&& splats);
  void finish_pass();

 private:
  void apply(size_t tile);
  std::mutex m_mutex;
  std::vector<std::vector<Splat>> m_pending;
  std::vector<char> m_ready;
  size_t m_next = 0;
  std::vector<Rgbd>& m_image;
};

}  // namespace dp::integrators
