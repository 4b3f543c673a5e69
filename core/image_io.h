// Image files. EXR: multi-layer float RGB; the layer named "" (or "RGB") is stored as
// channels R, G, B, every other layer as "<layer>.R", "<layer>.G", "<layer>.B" (the
// OpenEXR convention). PNG: 8-bit sRGB preview, values clamped to [0,1] after an
// optional exposure scale. LDR reads (PNG/JPEG) are decoded sRGB -> linear.
// All functions throw dp::IoError naming the file on failure. Writes go through
// core/atomic_write.h: a killed process leaves the old file or none, never a truncated one.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace dp::core {

struct NamedLayer {
  std::string name;  // "" = main RGB image
  Image image;
};

void write_exr(const std::string& path, const std::vector<NamedLayer>& layers);
void write_exr(const std::string& path, const Image& image);
// Reads every RGB layer of an EXR. Channels not grouped as R/G/B triples are ignored;
// a layer with only one of R/G/B is filled from it (grey). Half and float are accepted.
std::vector<NamedLayer> read_exr_layers(const std::string& path);
// Reads the main (unnamed) layer, or the only layer if there is exactly one.
Image read_exr(const std::string& path);

void write_png(const std::string& path, const Image& image, float exposure_scale = 1.0f);
// PNG/JPEG/... via stb_image; decodes sRGB to linear unless `linear` is set.
Image read_ldr(const std::string& path, bool linear = false);
// Reads by extension: .exr -> read_exr, otherwise read_ldr.
Image read_image(const std::string& path);

float srgb_to_linear(float v);
float linear_to_srgb(float v);

}  // namespace dp::core
