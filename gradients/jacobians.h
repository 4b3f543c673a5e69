// Shift-mapping Jacobians and the half-vector copy rules, in double (DESIGN.md, Numerics).
// Parameterization: a path is its raster position plus the solid-angle directions
// sampled at its vertices; a shift maps the base directions w_1..w_k to the offset
// directions w'_1..w'_k. The map is lower triangular (w'_m depends on w_1..w_m only), so
// its Jacobian determinant is the product of the per-direction factors below
// (Kettunen et al. 2015, Sec. 5.2; Lehtinen et al. 2013, Sec. 4.2).
#pragma once

#include <optional>

#include "core/math.h"

namespace dp::gradients {

// Reconnection: the offset leaves x'_i toward the base vertex x_{i+1} = target.
// d w'_i / d w_i = |cos θ'| |x_{i+1} - x_i|^2 / (|cos θ| |x_{i+1} - x'_i|^2), cosines at
// the target w.r.t. its geometric normal (Kettunen 2015, Sec. 5.2, Eq. 11: area-to-
// solid-angle factors cos/d^2 of the two connecting segments).
double reconnection_jacobian(const Vec3d& base_prev, const Vec3d& offset_prev, const Vec3d& target,
                             const Vec3d& target_normal);

// Half-vector copy, reflection (Kettunen 2015, Sec. 5.2; Lehtinen 2013, Sec. 5.1):
// h = normalize(wi + wo), w'_o = reflect(w'_i, h); d w'_o / d w_o = |w'_o.h| / |w_o.h|
// (from d w_h / d w_o = 1 / (4 |w_o.h|), Walter et al. 2007, Eq. 14).
Vec3d reflection_half_vector(const Vec3d& wi, const Vec3d& wo);
Vec3d reflect_about(const Vec3d& wi, const Vec3d& h);
double reflection_jacobian(const Vec3d& wo, const Vec3d& wo_offset, const Vec3d& h);

// Half-vector copy, refraction with relative index eta = eta_o / eta_i: generalized
// half vector H = wi + eta wo (Walter 2007, Eq. 16), h = H / |H| oriented to +z.
// w'_o = refraction of w'_i about h (nullopt on total internal reflection or eta = 1).
// d w'_o / d w_o = (|H'|^2 / |H|^2) |w_o.h| / |w'_o.h| (Walter 2007, Eq. 17 applied to
// base and offset; Kettunen 2015, Sec. 5.2).
std::optional<Vec3d> refraction_half_vector(const Vec3d& wi, const Vec3d& wo, double eta);
std::optional<Vec3d> refract_about(const Vec3d& wi, const Vec3d& h, double eta);
double refraction_jacobian(const Vec3d& wi, const Vec3d& wo, const Vec3d& wi_offset, const Vec3d& wo_offset,
                           double eta);

}  // namespace dp::gradients
