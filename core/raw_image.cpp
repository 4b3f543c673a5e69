#include "core/raw_image.h"

#include "core/error.h"

namespace dp::core {

namespace {
template <class Map>
std::string names(const Map& m) {
  std::string s;
  for (const auto& [k, v] : m) s += (s.empty() ? "" : ", ") + k;
  return s.empty() ? "none" : s;
}
template <class Map>
bool same_names(const Map& a, const Map& b) {
  if (a.size() != b.size()) return false;
  for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
    if (i->first != j->first) return false;
  return true;
}
}  // namespace

std::string RawImage::layout_difference(const RawImage& o) const {
  if (width != o.width || height != o.height)
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " vs " + std::to_string(o.width) + "x" +
           std::to_string(o.height);
  if (!same_names(sums, o.sums)) return "sum buffers (" + names(sums) + ") vs (" + names(o.sums) + ")";
  if (!same_names(counts, o.counts)) return "count buffers (" + names(counts) + ") vs (" + names(o.counts) + ")";
  return {};
}

void RawImage::add(const RawImage& o) {
  DP_CHECK(layout_difference(o).empty(), "RawImage::add: different layouts");
  for (auto& [name, v] : sums) {
    const auto& w = o.sums.at(name);
    for (size_t i = 0; i < v.size(); ++i) v[i] += w[i];
  }
  for (auto& [name, v] : counts) {
    const auto& w = o.counts.at(name);
    for (size_t i = 0; i < v.size(); ++i) v[i] += w[i];
  }
}

const std::vector<Rgbd>& RawImage::sum(const std::string& name) const {
  const auto it = sums.find(name);
  if (it == sums.end()) throw ValueError("raw buffers lack the sum '" + name + "' (have: " + names(sums) + ")");
  return it->second;
}

const std::vector<int64_t>& RawImage::count(const std::string& name) const {
  const auto it = counts.find(name);
  if (it == counts.end()) throw ValueError("raw buffers lack the count '" + name + "' (have: " + names(counts) + ")");
  return it->second;
}

}  // namespace dp::core
