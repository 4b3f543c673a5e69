// Primary-sample-space mutation kernels (Kelemen et al. 2002, Sec. 3.2; Mitsuba's PSSMLT).
// A state is a vector of coordinates in [0, 1) (pathspace::PrimarySampleStream records it).
//  * large step: every coordinate is replaced by a fresh uniform value (independent
//    proposal, density 1 on the unit cube: symmetric);
//  * small step: every coordinate is moved by +-s2 * exp(-log(s2 / s1) * u), u uniform
//    (so log|d| is uniform on [log s1, log s2], each sign with probability 1/2), and
//    wrapped into [0, 1). The density of y given x depends only on the wrapped
//    difference y - x and is even in it, so K(x -> y) = K(y -> x) on the torus.
// Both kernels are symmetric, so Metropolis-Hastings accepts with min(1, f(y) / f(x)).
#pragma once

#include <vector>

#include "core/rng.h"

namespace dp::mcmc {

struct KelemenKernel {
  double s1 = 1.0 / 1024.0;  // smallest perturbation (Kelemen 2002; Mitsuba default)
  double s2 = 1.0 / 64.0;    // largest perturbation

  // The signed offset d of one small step (|d| in [s1, s2]).
  double offset(core::Rng& rng) const;
  // x moved by one small step, wrapped into [0, 1).
  float perturb(float x, core::Rng& rng) const;
  // Every coordinate of `u` perturbed in place.
  void perturb_all(std::vector<float>& u, core::Rng& rng) const;
};

// Wraps a real number into [0, 1) as a float (never returns 1.0f).
float wrap_unit(double x);

}  // namespace dp::mcmc
