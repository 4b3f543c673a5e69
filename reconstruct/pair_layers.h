// Pair-gradient layers: the rows of any pixel-pair kernel (problem.h) and their sampled
// values stored as image layers, so that one EXR holds both the pair list and the pair
// gradients (`deltapath reconstruct --in` solves it; gdmlt writes it for kernel=adaptive,
// Manzi et al. 2014 Sec. 3.5).
//
// Rows are grouped by their end pixel b (row: I[b] - I[a] = value). The k-th row ending
// at pixel b (in kernel order) is stored at pixel b of two layers:
//   pairs.<k>         RGB: the row's value;
//   pairs.<k>.offset  R = x(a) - x(b), G = y(a) - y(b) (whole pixels), B = 1 where the
//                     row exists and 0 where pixel b has fewer than k+1 rows.
// k runs over 0 .. (most rows ending at one pixel) - 1.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"
#include "reconstruct/problem.h"

namespace dp::reconstruct {

struct PairLayers {
  std::vector<core::Image> values;   // pairs.<k>
  std::vector<core::Image> offsets;  // pairs.<k>.offset
};

std::string pair_value_layer(int k);   // "pairs.<k>"
std::string pair_offset_layer(int k);  // "pairs.<k>.offset"

// Throws dp::ValueError unless b has one value per kernel row.
PairLayers encode_pair_layers(const Kernel& kernel, const std::vector<Rgb>& b);

// The kernel (rows ordered by end pixel, then k) and its row values. Throws dp::ValueError
// (naming `where`) for layers of different sizes, a missing offset layer, or an offset
// that is not a whole number, is (0, 0), or leaves the image.
void decode_pair_layers(const PairLayers& layers, Kernel& kernel, std::vector<Rgb>& b, const std::string& where);

// Moves every "pairs.<k>" / "pairs.<k>.offset" layer (k = 0, 1, ... without gaps) out of
// `layers`; empty values when there is none.
PairLayers take_pair_layers(std::vector<core::NamedLayer>& layers);

// Appends the layers (names above) to `out`.
void append_pair_layers(PairLayers layers, std::vector<core::NamedLayer>& out);

}  // namespace dp::reconstruct
