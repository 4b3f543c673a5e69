// Factory functions for every material of the scene format (SCENE_FORMAT.md) and of
// the Mitsuba importer. Implementations live in bsdf_<name>.cpp. All parameters are
// validated by the front ends before calling these (they only DP_CHECK).
#pragma once

#include "scene/bsdf/bsdf.h"
#include "scene/bsdf/texture.h"

namespace dp::scene {

enum class MicrofacetType { beckmann, ggx };

// Fresnel of a conductor: Schlick with RGB F0, or the exact conductor Fresnel with a
// complex index eta + i k per RGB channel.
struct ConductorFresnel {
  enum class Kind { schlick, complex } kind = Kind::schlick;
  Rgb f0 = Rgb::Ones();
  Rgb eta = Rgb::Ones(), k = Rgb::Zero();
};

// Lambertian, albedo / pi. One-sided (upper hemisphere); wrap with make_two_sided.
BsdfPtr make_diffuse(TexturePtr albedo);
// Normalized modified Phong: diffuse/pi + specular (n + 2) / (2 pi) max(0, cos a)^n,
// a = angle between reflect(wi) and wo.
BsdfPtr make_phong(TexturePtr diffuse, TexturePtr specular, float exponent);
// Ideal mirror.
BsdfPtr make_mirror(TexturePtr reflectance);
// Dielectric interface; roughness (microfacet alpha) 0 = smooth (delta lobes), else
// Walter et al. 2007 rough dielectric.
BsdfPtr make_dielectric(float int_ior, float ext_ior, float roughness, MicrofacetType dist,
                        TexturePtr specular_reflectance = nullptr, TexturePtr specular_transmittance = nullptr);
// Thin dielectric sheet (Mitsuba thindielectric): delta reflection + straight transmission.
BsdfPtr make_thin_dielectric(float int_ior, float ext_ior);
// Conductor; alpha 0 = smooth mirror with Fresnel. Anisotropic alpha_u/alpha_v allowed.
BsdfPtr make_conductor(float alpha_u, float alpha_v, MicrofacetType dist, const ConductorFresnel& fresnel,
                       TexturePtr specular_reflectance = nullptr);
// Diffuse base under a dielectric coating (Mitsuba plastic/roughplastic semantics);
// roughness 0 = smooth coating.
BsdfPtr make_plastic(TexturePtr diffuse, float int_ior, float ext_ior, float roughness, MicrofacetType dist,
                     bool nonlinear = false, TexturePtr specular_reflectance = nullptr);
// Evaluates `inner` on whichever side wi is (both directions flipped to the upper
// hemisphere); for opaque (reflection-only) BSDFs.
BsdfPtr make_two_sided(BsdfPtr inner);
// Pass-through surface: delta transmission wo = -wi with weight 1 (Mitsuba null).
BsdfPtr make_null();
// Stochastic opacity: with probability opacity scatter by `inner`, else pass through.
BsdfPtr make_mask(BsdfPtr inner, TexturePtr opacity);

}  // namespace dp::scene
