#include "reconstruct/pair_layers.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"

namespace dp::reconstruct {

std::string pair_value_layer(int k) { return "pairs." + std::to_string(k); }
std::string pair_offset_layer(int k) { return "pairs." + std::to_string(k) + ".offset"; }

PairLayers encode_pair_layers(const Kernel& kernel, const std::vector<Rgb>& b) {
  if (b.size() != kernel.rows())
    throw ValueError("reconstruct: " + std::to_string(b.size()) + " pair values for " +
                     std::to_string(kernel.rows()) + " kernel rows");
  const int w = kernel.width(), h = kernel.height();
  std::vector<int> count(kernel.pixels(), 0);  // rows ending at each pixel so far
  PairLayers out;
  for (size_t r = 0; r < kernel.rows(); ++r) {
    const PixelPair& p = kernel.pairs()[r];
    const int k = count[size_t(p.j)]++;
    if (size_t(k) == out.values.size()) {
      out.values.emplace_back(w, h);
      out.offsets.emplace_back(w, h);
    }
    out.values[size_t(k)][size_t(p.j)] = b[r];
    out.offsets[size_t(k)][size_t(p.j)] =
        Rgb(float(p.i % w - p.j % w), float(p.i / w - p.j / w), 1.0f);
  }
  return out;
}

void decode_pair_layers(const PairLayers& layers, Kernel& kernel, std::vector<Rgb>& b, const std::string& where) {
  if (layers.values.empty()) throw ValueError("no pair layers (pairs.0, pairs.0.offset)", where);
  if (layers.values.size() != layers.offsets.size())
    throw ValueError(std::to_string(layers.values.size()) + " pair value layers but " +
                         std::to_string(layers.offsets.size()) + " offset layers",
                     where);
  const core::Image& first = layers.values[0];
  for (size_t k = 0; k < layers.values.size(); ++k)
    if (!layers.values[k].same_size(first) || !layers.offsets[k].same_size(first))
      throw ValueError("layer " + pair_value_layer(int(k)) + " or its offset layer differs in size from pairs.0",
                       where);
  const int w = first.width(), h = first.height();
  std::vector<PixelPair> pairs;
  b.clear();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (size_t k = 0; k < layers.values.size(); ++k) {
        const Rgb& o = layers.offsets[k](x, y);
        if (o.z() == 0.0f) continue;
        const float ox = o.x(), oy = o.y();
        const auto bad = [&](const std::string& why) {
          return ValueError(pair_offset_layer(int(k)) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                "): " + why,
                            where);
        };
        if (!(o.z() == 1.0f) || !(std::isfinite(ox) && std::isfinite(oy)) || ox != std::round(ox) ||
            oy != std::round(oy))
          throw bad("offset must be whole pixels with B = 0 or 1");
        const int ax = x + int(ox), ay = y + int(oy);
        if (ox == 0.0f && oy == 0.0f) throw bad("a pair joins the pixel to itself");
        if (ax < 0 || ay < 0 || ax >= w || ay >= h) throw bad("the partner pixel is outside the image");
        pairs.push_back({ay * w + ax, y * w + x});
        b.push_back(layers.values[k](x, y));
      }
  kernel = Kernel(w, h, std::move(pairs));
}

PairLayers take_pair_layers(std::vector<core::NamedLayer>& layers) {
  PairLayers out;
  for (int k = 0;; ++k) {
    auto value = std::find_if(layers.begin(), layers.end(), [&](const auto& l) { return l.name == pair_value_layer(k); });
    auto offset =
        std::find_if(layers.begin(), layers.end(), [&](const auto& l) { return l.name == pair_offset_layer(k); });
    if (value == layers.end() && offset == layers.end()) break;
    out.values.push_back(value == layers.end() ? core::Image() : std::move(value->image));
    out.offsets.push_back(offset == layers.end() ? core::Image() : std::move(offset->image));
  }
  return out;
}

void append_pair_layers(PairLayers layers, std::vector<core::NamedLayer>& out) {
  for (size_t k = 0; k < layers.values.size(); ++k) {
    out.push_back({pair_value_layer(int(k)), std::move(layers.values[k])});
    out.push_back({pair_offset_layer(int(k)), std::move(layers.offsets[k])});
  }
}

}  // namespace dp::reconstruct
