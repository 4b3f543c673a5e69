#include "experiments/scoring.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/metrics.h"

namespace dp::experiments {

size_t scored_layer(const std::vector<core::NamedLayer>& layers, const std::string& reconstruction) {
  DP_CHECK(!layers.empty(), "render produced no layers");
  if (!reconstruction.empty()) {
    const std::string wanted = "recon_" + reconstruction;
    for (size_t i = 0; i < layers.size(); ++i)
      if (layers[i].name == wanted) return i;
  }
  return 0;
}

double evaluate_metric(const Metric& metric, const core::Image& image, const core::Image& reference,
                       const std::vector<Crop>& crops) {
  if (metric.crop >= 0) {
    DP_CHECK(size_t(metric.crop) < crops.size(), "metric crop index out of range");
    Metric whole = metric;
    whole.crop = -1;
    const Crop& c = crops[size_t(metric.crop)];
    return evaluate_metric(whole, crop_image(image, c, 1), crop_image(reference, c, 1));
  }
  if (metric.name == "relmse") return core::relmse(image, reference, metric.discard);
  if (metric.name == "mse") return core::mse(image, reference, metric.discard);
  if (metric.name == "mape") return core::compare(image, reference, metric.discard).mape;
  throw ValueError("unknown metric '" + metric.name + "'");
}

Rgb error_ramp(double t) {
  // Piecewise-linear dark blue -> teal -> green -> yellow (perceptually ordered).
  static const float kStops[5][3] = {
      {0.05f, 0.03f, 0.35f}, {0.15f, 0.35f, 0.60f}, {0.10f, 0.60f, 0.55f}, {0.50f, 0.80f, 0.25f}, {0.99f, 0.91f, 0.15f}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(int(t), 3);
  const auto f = float(t - double(i));
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = kStops[i][k] * (1.0f - f) + kStops[i + 1][k] * f;
  return c;
}

core::Image error_map(const core::Image& image, const core::Image& reference) {
  DP_CHECK(image.same_size(reference), "error_map: image sizes differ");
  core::Image out(image.width(), image.height());
  for (size_t i = 0; i < image.size(); ++i) {
    if (!is_finite(image[i])) {
      out[i] = Rgb(1.0f, 0.0f, 1.0f);
      continue;
    }
    double e = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = double(image[i][c]) - double(reference[i][c]);
      e += d * d / (double(reference[i][c]) * double(reference[i][c]) + core::kRelMseEpsilon);
    }
    e /= 3.0;
    const double l = e > 0 ? std::log10(e) : kErrorMapLog10Min;
    // The PNG writer applies the sRGB curve: store linear values of the ramp's colours.
    const Rgb srgb = error_ramp((l - kErrorMapLog10Min) / (kErrorMapLog10Max - kErrorMapLog10Min));
    for (int c = 0; c < 3; ++c) out[i][c] = core::srgb_to_linear(srgb[c]);
  }
  return out;
}

core::Image crop_image(const core::Image& image, const Crop& crop, int min_size) {
  DP_CHECK(crop.x >= 0 && crop.y >= 0 && crop.x + crop.w <= image.width() && crop.y + crop.h <= image.height(),
           "crop outside the image");
  const int scale = std::max(1, (min_size + std::max(crop.w, crop.h) - 1) / std::max(crop.w, crop.h));
  core::Image out(crop.w * scale, crop.h * scale);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out(x, y) = image(crop.x + x / scale, crop.y + y / scale);
  return out;
}

}  // namespace dp::experiments
