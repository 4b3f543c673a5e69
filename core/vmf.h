// The von Mises-Fisher distribution on the unit sphere about a mean direction mu with
// concentration kappa (Wenzel Jakob, "Numerically stable sampling of the von Mises
// Fisher distribution on S^2", 2012): density
//   p(w) = kappa / (2 pi (1 - exp(-2 kappa))) exp(kappa (mu.w - 1))   (solid angle),
// sampled by inverting the CDF of mu.w. Double precision throughout (kappa reaches 1e5
// in the manifold perturbation, where 1 - cos theta ~ 1e-5).
#pragma once

#include <cmath>

#include "core/math.h"

namespace dp::core {

// Density of a direction at cos theta = mu.w.
inline double vmf_pdf(double kappa, double cos_theta) {
  return kappa / (2.0 * kPiD * -std::expm1(-2.0 * kappa)) * std::exp(kappa * (cos_theta - 1.0));
}

// cos theta and phi of a sample for uniforms u1, u2 in [0, 1).
inline void vmf_sample(double kappa, double u1, double u2, double& cos_theta, double& phi) {
  // 1 + log(u1 + (1 - u1) exp(-2 kappa)) / kappa, written to stay accurate for large kappa.
  cos_theta = 1.0 + std::log1p((1.0 - u1) * std::expm1(-2.0 * kappa)) / kappa;
  cos_theta = std::max(-1.0, std::min(1.0, cos_theta));
  phi = 2.0 * kPiD * u2;
}

}  // namespace dp::core
