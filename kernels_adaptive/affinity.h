// Pixel affinity of Manzi et al. 2014, Eq. 7, and the choice of each pixel's n most
// similar pixels (Sec. 3.5 "Pixel affinity", Fig. 7; parameters of Sec. 5):
//     omega_k(i, j) = exp(-max(0, |phi_k(i) - phi_k(j)|^2 - tau_k) / sigma_k^2),
//     omega(i, j)   = min_k omega_k(i, j),     k in {normal, texture, depth},
// with |.|^2 the squared Euclidean distance over the feature's channels (features in
// [0, 1], features.h).
//
// With sigma = 0.01 the weights underflow (to 0, even in double) as soon as a feature
// differs by more than ~0.27 beyond its threshold, so pixels are ranked by the exponent
//     cost(i, j) = max_k max(0, |phi_k(i) - phi_k(j)|^2 - tau_k) / sigma_k^2
// (omega = exp(-cost), exp is decreasing: the same order, without ties from underflow).
// Ties in cost go to the spatially nearer pixel (squared pixel distance), then to the
// smaller pixel index: in a region of constant features the choice is the 4-neighbourhood.
#pragma once

#include <cstdint>
#include <vector>

#include "kernels_adaptive/features.h"

namespace dp::kernels_adaptive {

struct AffinityParams {
  // Manzi et al. 2014, Sec. 5: sigma_k = 0.01 for all features; tau_normal = 0.02,
  // tau_texture = 0.001, tau_depth = 0.01; 5 x 5 window; n = 4.
  float sigma_normal = 0.01f, sigma_texture = 0.01f, sigma_depth = 0.01f;
  float tau_normal = 0.02f, tau_texture = 0.001f, tau_depth = 0.01f;
  int window = 5;      // side of the square window centred on the pixel (odd, >= 3)
  int neighbours = 4;  // n: partners chosen per pixel (fewer only if the window has fewer)
};

// Throws dp::ValueError for sigma <= 0, tau < 0 or non-finite, an even or < 3 window,
// or neighbours < 1.
void validate(const AffinityParams& params);

// One factor of Eq. 7 from the squared feature distance d2.
double feature_affinity(double d2, double tau, double sigma);
// The exponent cost(i, j) above (>= 0; omega = exp(-cost)).
double affinity_cost(const Features& f, int32_t i, int32_t j, const AffinityParams& params);
// omega(i, j) = min_k omega_k (Eq. 7).
double affinity(const Features& f, int32_t i, int32_t j, const AffinityParams& params);

// The pixels j != i in i's window (clipped to the image) with the n largest omega(i, j),
// best first, ties broken as described above. Does not validate its inputs.
std::vector<int32_t> most_similar(const Features& f, int32_t i, const AffinityParams& params);

}  // namespace dp::kernels_adaptive
