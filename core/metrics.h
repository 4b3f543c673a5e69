// Image error metrics, accumulated in double.
//  mse    = mean over pixels and channels of (X - R)^2
//  relmse = mean over pixels and channels of (X - R)^2 / (R^2 + eps), eps = 1e-3
//           (the gradient-domain papers' definition, evaluated per channel)
//  mape   = mean over pixels and channels of |X - R| / (|R| + 1e-2)
// `discard` drops the n pixels with the largest per-pixel error before averaging.
// Non-finite pixels of X are excluded and counted (ErrorReport::nonfinite).
#pragma once

#include <cstddef>

#include "core/image.h"

namespace dp::core {

constexpr double kRelMseEpsilon = 1e-3;

struct ErrorReport {
  double mse = 0;
  double relmse = 0;
  double mape = 0;
  Rgbd mean_image = Rgbd::Zero();
  Rgbd mean_reference = Rgbd::Zero();
  Rgbd mean_ratio = Rgbd::Zero();  // mean(X)/mean(R) per channel
  size_t nonfinite = 0;           // pixels of X excluded because non-finite
};

double mse(const Image& x, const Image& ref, size_t discard = 0);
double relmse(const Image& x, const Image& ref, size_t discard = 0, double eps = kRelMseEpsilon);
ErrorReport compare(const Image& x, const Image& ref, size_t discard = 0);

}  // namespace dp::core
