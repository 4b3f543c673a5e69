// Distance sampling and transmittance in a homogeneous medium with RGB coefficients.
// Free-flight sampling picks one colour channel c uniformly and draws
// t ~ sigma_t[c] exp(-sigma_t[c] t); the estimator weights by the density of the whole
// one-sample mixture over the three channels (the balance heuristic over channels, as
// pbrt-v3's HomogeneousMedium::Sample):
//   p(t)      = 1/3 sum_c sigma_t[c] exp(-sigma_t[c] t)      scatter at t < t_max
//   P(pass)   = 1/3 sum_c exp(-sigma_t[c] t_max)             no scatter before t_max
//   weight    = Tr(t) sigma_s / p(t)    or    Tr(t_max) / P(pass)
// with Tr(d) = exp(-sigma_t d) per channel (Beer-Lambert). The expected weight of the
// pass branch is Tr(t_max) and that of the scatter branch integrates
// Tr(t) sigma_s over [0, t_max) (Gruson et al. 2018, Eqs. 2-3: tau and the medium
// vertex's sigma_s). Distances are in world units; t_max may be +inf (a ray leaving
// the scene): channels with sigma_t = 0 then pass with Tr = 1, the others never do.
#pragma once

#include "core/math.h"
#include "scene/media/medium.h"

namespace dp::scene {

struct FreeFlightSample {
  float t = 0;            // the scatter distance, or t_max when the ray passed
  bool scattered = false;
  Rgb weight = Rgb::Ones();  // see the header comment; 0 when nothing can be estimated
  float pdf = 0;          // p(t) if scattered, P(pass) otherwise
  int channel = 0;        // the channel that drew t
};

// Beer-Lambert transmittance exp(-sigma_t d), 1 where sigma_t = 0 (also for d = inf).
Rgb transmittance(const HomogeneousMedium& m, float d);
// Integral of Tr(t) dt over [a, b] (0 <= a <= b < inf), per channel
// (exp(-sigma_t a) - exp(-sigma_t b)) / sigma_t = exp(-sigma_t a) (-expm1(-sigma_t (b - a))) / sigma_t,
// and b - a where sigma_t = 0: the camera side of a 3D-kernel beam query (Gruson et al.
// 2018, Sec. 5.1, Point-Beam 3D; integrators/bre/bre_gather.h).
Rgb integrated_transmittance(const HomogeneousMedium& m, float a, float b);
// The mixture density p(t) of a scatter at distance t (t >= 0).
float free_flight_pdf(const HomogeneousMedium& m, float t);
// The probability P(pass) of no scatter before t_max.
float free_flight_pass_probability(const HomogeneousMedium& m, float t_max);
// One free-flight sample along a ray segment of length t_max (> 0, may be inf);
// u_channel, u in [0, 1).
FreeFlightSample sample_free_flight(const HomogeneousMedium& m, float t_max, float u_channel, float u);

}  // namespace dp::scene
