#include "integrators/media_photons/volume_kernel.h"

#include <cmath>

#include "core/math.h"

namespace dp::integrators {

double uniform_kernel(int dim, double r) {
  const double pi = double(kPi);
  return dim == 3 ? 3.0 / (4.0 * pi * r * r * r) : 1.0 / (pi * r * r);
}

double progressive_radius(double r1, int64_t index, double alpha, int dim) {
  // prod_{i=1}^{n} (i + alpha) / (i + 1) = Gamma(n + 1 + alpha) / (Gamma(1 + alpha) Gamma(n + 2)),
  // n = index (Knaus & Zwicker 2011, Sec. 4.3), through lgamma: no O(n) product, and a
  // part of a split render gets the same radius for the same global index.
  const double n = double(index);
  const double log_ratio = std::lgamma(n + 1.0 + alpha) - std::lgamma(1.0 + alpha) - std::lgamma(n + 2.0);
  return r1 * std::exp(log_ratio / double(dim));
}

}  // namespace dp::integrators
