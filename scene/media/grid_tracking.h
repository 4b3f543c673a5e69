// Free flights and transmittance in a grid medium (medium.h with a DensityGrid): sigma_t(x)
// = density(x) s with a grey s, majorant mu = s max(density) over the grid's box, outside
// of which the medium is empty (density 0).
//  * Delta (Woodcock) tracking: tentative collisions at exponential steps of rate mu from
//    the box's entry point; each is real with probability sigma_t(x) / mu, else null and
//    tracking goes on. The first real collision is distributed with density
//    sigma_t(t) Tr(t) (Tr(t) = exp(-int_0^t sigma_t)), so a scatter's weight is
//    Tr sigma_s / p = sigma_s / sigma_t = the albedo (per channel) and a pass has weight 1:
//    the same expected weights as free_flight.h's homogeneous estimator.
//  * Ratio tracking: the product of (1 - sigma_t(x_i) / mu) over the tentative collisions
//    before t_max, an unbiased estimate of Tr(t_max) (Novak et al. 2014).
// Both draw from `rng` and take the ray in world space (o, unit d) and its length t_max
// (may be +inf: the box bounds the work).
#pragma once

#include "core/math.h"
#include "core/rng.h"
#include "scene/media/free_flight.h"
#include "scene/media/medium.h"

namespace dp::scene {

// Deliberate defects for the tests (test_grid_media.cpp). C++ only.
enum class GridTrackingFault : uint8_t {
  none,
  majorant_from_mean,  // mu from the mean density instead of the maximum (collisions missed where denser)
};

// A free flight by delta tracking. `pdf` is 0 (not available for grids); `channel` 0.
FreeFlightSample sample_free_flight_grid(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max,
                                         core::Rng& rng, GridTrackingFault fault = GridTrackingFault::none);
// Ratio-tracking estimate of the transmittance over [0, t_max] (grey).
Rgb transmittance_grid(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max, core::Rng& rng,
                       GridTrackingFault fault = GridTrackingFault::none);

}  // namespace dp::scene
