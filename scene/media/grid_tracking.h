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

#include <vector>

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

// Ratio tracking along [0, t_max] kept as a step function of the distance (for the photon
// density estimators' camera segments, integrators/vpm, integrators/bre): Tr_hat(t) = the
// product of (1 - sigma_t(x_i) / mu) over the tentative collisions t_i < t. For each t it
// is exactly ratio tracking stopped at t, so it is unbiased for Tr(t) at every t at once
// (the estimates at different t are correlated), and by linearity its integral over
// [a, b] is unbiased for int_a^b Tr (BRE's 3D kernel, Gruson et al. 2018, Sec. 5.1).
class TransmittanceProfile {
 public:
  void track(const HomogeneousMedium& m, const Vec3& o, const Vec3& d, float t_max, core::Rng& rng);
  float at(float t) const;                 // Tr_hat(t), t >= 0
  float integral(float a, float b) const;  // int_a^b Tr_hat(t) dt, 0 <= a <= b < inf
  size_t collisions() const { return m_t.size(); }

 private:
  std::vector<float> m_t;  // tentative collision distances, ascending
  std::vector<float> m_v;  // Tr_hat just after each
};

}  // namespace dp::scene
