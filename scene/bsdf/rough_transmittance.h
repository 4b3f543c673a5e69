// Energy transmitted through a rough dielectric interface (Walter et al. 2007 BTDF with
// separable Smith G), as used by the rough plastic's internal-scattering term.
// Contract: eval(mu) = \int f_t(wi, wo) |cos wo| dwo for wi at cos(theta) = mu > 0 on
// the side the normal points to, in the physical (importance) normalization, i.e.
// without the radiance 1/eta^2 scaling; eta = eta_other_side / eta_incident_side.
// Computed once at construction by deterministic stratified quadrature over the
// visible normals: T(mu) = E_{m ~ D_wi}[(1 - F(wi.m)) G1(wt, m)] (substituting
// Walter 2007, Eq. 21 and the Jacobian Eq. 17 into the integral), tabulated over mu
// and interpolated linearly.
#pragma once

#include <vector>

#include "scene/bsdf/microfacet.h"

namespace dp::scene {

class RoughTransmittance {
 public:
  RoughTransmittance(MicrofacetType type, float alpha, float eta, int nodes = 64, int strata = 48);
  // Transmittance for an incident direction with cosine mu in (0, 1].
  float eval(float mu) const;
  // Cosine-weighted hemispherical average 2 \int_0^1 T(mu) mu dmu (diffuse illumination).
  float diffuse() const { return m_diffuse; }
  // Direct (untabulated) quadrature of T(mu), used to build the table and in tests.
  static float compute(const Microfacet& distr, float eta, float mu, int strata);

 private:
  std::vector<float> m_table;  // T at mu_j = j / (n - 1), j = 0..n-1
  float m_diffuse = 0;
};

}  // namespace dp::scene
