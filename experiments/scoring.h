// Scoring one render against the reference.
//
// Which layer is scored: a run with `reconstruction: l1|l2` is scored on the layer
// "recon_l1" / "recon_l2" when the integrator wrote one (gradient-domain integrators),
// otherwise on layers[0], the final image. Runs without `reconstruction` are scored on
// layers[0] (for G-PT that is the reconstruction its own `reconstruction` setting picks).
//
// Metrics are core/metrics.h's (relMSE with eps 1e-3 as in the papers, MSE, MAPE), each
// optionally discarding the n pixels with the largest error.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"
#include "experiments/config.h"

namespace dp::experiments {

// Index into `layers` of the layer to score (see above).
size_t scored_layer(const std::vector<core::NamedLayer>& layers, const std::string& reconstruction);

// `crops`: the config's crops (a metric with `crop` is scored on that region only).
double evaluate_metric(const Metric& metric, const core::Image& image, const core::Image& reference,
                       const std::vector<Crop>& crops = {});

// False-colour map of the per-pixel relative squared error (mean over channels of
// (X - R)^2 / (R^2 + 1e-3)), log10-scaled from kErrorMapLog10Min (dark blue) to
// kErrorMapLog10Max (yellow); non-finite pixels are magenta.
constexpr double kErrorMapLog10Min = -4.0;
constexpr double kErrorMapLog10Max = 1.0;
core::Image error_map(const core::Image& image, const core::Image& reference);
// The colour ramp of error_map at t in [0, 1] (the report draws its legend from it).
Rgb error_ramp(double t);

// The crop region, scaled up by pixel replication by an integer factor so that its
// longer side is at least `min_size` pixels. Requires the crop to be inside the image.
core::Image crop_image(const core::Image& image, const Crop& crop, int min_size = 128);

}  // namespace dp::experiments
