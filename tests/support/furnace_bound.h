// Round-off bound of one sampled gradient in the closed diffuse furnace sphere (radius R,
// camera inside; tests/support/test_scenes.h): every concrete path has f/p = albedo^k Le
// and a reconnection shift preserves it exactly (chord property cos_a cos_b / d^2 =
// 1/(4R^2)), so an offset's value differs from its base's only through float geometry:
//  * a chord a -> b has cos_a cos_b / d^2 = 1/(4R^2) exactly; with float points off the
//    sphere by dr <= (sqrt(3)/2) u |p| (u = 2^-24) the product becomes
//    (1 - ((|a|^2 - |b|^2)/d^2)^2)/(4|a||b|): the radial rounding cancels to first order
//    inside every chord that is evaluated from positions;
//  * a walk's cosine at x_k comes from the SAMPLED direction, and x_{k+1} lies on that ray
//    only up to the rounding of the hit, d_perp <= ~4u (1 + |p|) (hit distance, point,
//    re-projection onto the sphere, each rounded once): a first-order relative error
//    d_perp / (d cos) = 2R d_perp / d^2 -- the dominant term;
//  * float evaluation of BSDFs, cosines, normalizations: a few dozen roundings, <= 64u.
// Hence |value(T x) - value(x)| / value(x) <= eps(d_min) with d_min the shortest segment of
// the base or any offset (used by test_gpt_furnace.cpp and test_gbdpt_shift.cpp).
#pragma once

namespace dp::test {

inline double furnace_roundoff_bound(double d_min, double R = 1.0) {
  constexpr double u = 0x1p-24;
  const double d_perp = 4.0 * u * (1.0 + R), dr = 0.8660254 * u * R;
  const double q = 4.0 * R * dr / (d_min * d_min);
  return 64.0 * u + 2.0 * R * d_perp / (d_min * d_min) + q * q;
}

}  // namespace dp::test
