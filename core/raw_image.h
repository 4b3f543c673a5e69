// Raw accumulation buffers of a render: per-pixel sums (not averages) in double and
// per-pixel sample counts, by name. This is the exchange form of `render --partial` and
// `merge` (issue 17): adding two RawImages of the same render split into disjoint shares
// gives the RawImage of the whole render. Integrators keep typed buffers internally and
// convert at the border; the names are fixed by each integrator (e.g. "primal", "dx").
// Stored losslessly in EXR by core/image_io_raw.h.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/math.h"

namespace dp::core {

struct RawImage {
  int width = 0, height = 0;
  std::map<std::string, std::vector<Rgbd>> sums;       // row-major, width * height each
  std::map<std::string, std::vector<int64_t>> counts;  // row-major, width * height each

  size_t pixels() const { return size_t(width) * size_t(height); }
  // Empty when `other` has the same size and buffer names, else what differs (one line).
  std::string layout_difference(const RawImage& other) const;
  // Adds every sum and count of `other` (DP_CHECK: layout_difference is empty).
  void add(const RawImage& other);
  // The named buffer; throws dp::ValueError naming it when absent.
  const std::vector<Rgbd>& sum(const std::string& name) const;
  const std::vector<int64_t>& count(const std::string& name) const;
};

}  // namespace dp::core
