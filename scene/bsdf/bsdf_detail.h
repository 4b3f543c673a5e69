// Internal helpers shared by the bsdf_*.cpp files (not part of the public scene API).
#pragma once

#include "scene/bsdf/bsdfs.h"

namespace dp::scene::detail {

// Texture value at uv, or `fallback` when the texture is absent.
inline Rgb eval_or(const TexturePtr& tex, const Vec2& uv, float fallback = 1.0f) {
  return tex ? tex->eval(uv) : Rgb::Constant(fallback);
}
inline Rgb mean_or(const TexturePtr& tex, float fallback = 1.0f) {
  return tex ? tex->mean() : Rgb::Constant(fallback);
}
inline bool varies(const TexturePtr& tex) { return tex && !tex->is_constant(); }

// Mirror reflection about the local normal (0, 0, 1).
inline Vec3 reflect_local(const Vec3& w) { return Vec3(-w.x(), -w.y(), w.z()); }

// Refraction of w about m (Walter et al. 2007, Eq. 40), given c = w.m and the signed
// cosine cos_t and eta_ti = eta_t / eta_i from fresnel_dielectric(c, eta).
inline Vec3 refract_about(const Vec3& w, const Vec3& m, float c, float cos_t, float eta_ti) {
  return (cos_t + c / eta_ti) * m - w / eta_ti;
}

// Factories of the rough variants (make_dielectric / make_plastic dispatch on roughness).
BsdfPtr make_rough_dielectric(float int_ior, float ext_ior, float alpha, MicrofacetType dist,
                              TexturePtr specular_reflectance, TexturePtr specular_transmittance);
BsdfPtr make_rough_plastic(TexturePtr diffuse, float int_ior, float ext_ior, float alpha, MicrofacetType dist,
                           bool nonlinear, TexturePtr specular_reflectance);

}  // namespace dp::scene::detail
