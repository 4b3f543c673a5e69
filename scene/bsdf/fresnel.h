// Fresnel reflectance of smooth interfaces.
// Contract: cosines are measured against the interface normal on the incident side
// convention of each function (documented below); results are unpolarized energy
// reflectances in [0, 1].
#pragma once

#include "core/math.h"

namespace dp::scene {

struct DielectricFresnel {
  float reflectance = 1;  // F in [0, 1]; 1 on total internal reflection
  float cos_t = 0;        // cosine of the refracted direction, sign opposite to cos_i (0 on TIR)
  float eta_ti = 1;       // relative index eta_t / eta_i actually used
};

// Exact unpolarized Fresnel reflectance of a dielectric interface (Born & Wolf,
// Sec. 1.5.3; Walter et al. 2007, Eq. 22). `eta` = eta_interior / eta_exterior and
// the normal points to the exterior: cos_i > 0 means the incident direction is
// outside, cos_i < 0 inside (then eta_ti = 1/eta).
DielectricFresnel fresnel_dielectric(float cos_i, float eta);

// Exact unpolarized Fresnel reflectance of a conductor with complex relative index
// eta + i k, per RGB channel (Born & Wolf, Sec. 14.2; amplitude coefficients r_s, r_p
// evaluated in complex arithmetic). cos_i is taken in absolute value.
Rgb fresnel_conductor(float cos_i, const Rgb& eta, const Rgb& k);

// Schlick 1994, Eq. 15: F0 + (1 - F0) (1 - cos)^5; cos_i taken in absolute value.
float fresnel_schlick(float cos_i, float f0);
Rgb fresnel_schlick(float cos_i, const Rgb& f0);

// Hemispherical (cosine-weighted) average of the dielectric reflectance seen from the
// exterior side, Fdr(eta) = 2 \int_0^1 F(mu, eta) mu dmu, by Gauss-Legendre quadrature
// on the angular variable (handles the TIR kink for eta < 1 by splitting there).
float fresnel_diffuse_reflectance(float eta);

}  // namespace dp::scene
