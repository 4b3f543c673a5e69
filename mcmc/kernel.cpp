#include "mcmc/kernel.h"

#include <cmath>

namespace dp::mcmc {

float wrap_unit(double x) {
  x -= std::floor(x);
  const float f = float(x);
  return f < 1.0f ? f : 0.0f;  // x in [1 - 2^-25, 1) rounds up to 1.0f: that is 0 on the torus
}

double KelemenKernel::offset(core::Rng& rng) const {
  // Kelemen et al. 2002, Sec. 3.2: dv = s2 exp(-log(s2 / s1) u).
  const double mag = s2 * std::exp(-std::log(s2 / s1) * rng.uniform_double());
  return rng.uniform() < 0.5f ? mag : -mag;
}

float KelemenKernel::perturb(float x, core::Rng& rng) const { return wrap_unit(double(x) + offset(rng)); }

void KelemenKernel::perturb_all(std::vector<float>& u, core::Rng& rng) const {
  for (float& x : u) x = perturb(x, rng);
}

}  // namespace dp::mcmc
