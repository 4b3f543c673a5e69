// PNG/JPEG (and Radiance .hdr for reading) via Debian's libstb.
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <vector>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"

namespace dp::core {

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

void write_png(const std::string& path, const Image& image, float exposure_scale) {
  const int w = image.width(), h = image.height();
  std::vector<unsigned char> bytes(size_t(w) * size_t(h) * 3);
  for (size_t i = 0; i < image.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = image[i][c] * exposure_scale;
      if (!std::isfinite(v)) v = 0.0f;
      v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
      bytes[i * 3 + size_t(c)] = static_cast<unsigned char>(std::clamp(v * 255.0f + 0.5f, 0.0f, 255.0f));
    }
  }
  write_atomically(path, [&](const std::string& tmp) {
    if (!stbi_write_png(tmp.c_str(), w, h, 3, bytes.data(), w * 3)) throw IoError("cannot write PNG", path);
  });
}

Image read_ldr(const std::string& path, bool linear) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw IoError(std::string("cannot read image: ") + (why ? why : "unknown error"), path);
  }
  float lut[256];
  for (int i = 0; i < 256; ++i) lut[i] = linear ? float(i) / 255.0f : srgb_to_linear(float(i) / 255.0f);
  Image img(w, h);
  for (size_t i = 0; i < img.size(); ++i) img[i] = Rgb(lut[data[3 * i]], lut[data[3 * i + 1]], lut[data[3 * i + 2]]);
  stbi_image_free(data);
  return img;
}

// Radiance RGBE (.hdr, e.g. SmallVCM's output): linear floats, no transfer curve.
namespace {
Image read_hdr(const std::string& path) {
  int w = 0, h = 0, n = 0;
  float* data = stbi_loadf(path.c_str(), &w, &h, &n, 3);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw IoError(std::string("cannot read image: ") + (why ? why : "unknown error"), path);
  }
  Image img(w, h);
  for (size_t i = 0; i < img.size(); ++i) img[i] = Rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  stbi_image_free(data);
  return img;
}
}  // namespace

Image read_image(const std::string& path) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".exr") return read_exr(path);
  return ext == ".hdr" ? read_hdr(path) : read_ldr(path);
}

}  // namespace dp::core
