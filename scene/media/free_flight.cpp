#include "scene/media/free_flight.h"

#include <algorithm>
#include <cmath>

namespace dp::scene {

namespace {
// exp(-s d) with the convention 0 * inf = 0 (a channel without extinction never attenuates).
float beer(float s, float d) { return s > 0.0f ? std::exp(-s * d) : 1.0f; }
}  // namespace

Rgb transmittance(const HomogeneousMedium& m, float d) {
  const Rgb st = m.sigma_t();
  return Rgb(beer(st[0], d), beer(st[1], d), beer(st[2], d));
}

Rgb integrated_transmittance(const HomogeneousMedium& m, float a, float b) {
  const Rgb st = m.sigma_t();
  const double len = double(b) - double(a);
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const double s = double(st[c]);
    out[c] = s > 0.0 ? float(std::exp(-s * double(a)) * -std::expm1(-s * len) / s) : float(len);
  }
  return out;
}

float free_flight_pdf(const HomogeneousMedium& m, float t) {
  const Rgb st = m.sigma_t();
  return (st[0] * beer(st[0], t) + st[1] * beer(st[1], t) + st[2] * beer(st[2], t)) / 3.0f;
}

float free_flight_pass_probability(const HomogeneousMedium& m, float t_max) {
  const Rgb st = m.sigma_t();
  return (beer(st[0], t_max) + beer(st[1], t_max) + beer(st[2], t_max)) / 3.0f;
}

FreeFlightSample sample_free_flight(const HomogeneousMedium& m, float t_max, float u_channel, float u) {
  FreeFlightSample s;
  s.channel = std::min(int(u_channel * 3.0f), 2);
  const float st = m.sigma_t()[s.channel];
  // Inversion of the exponential CDF: t = -ln(1 - u) / sigma_t (u < 1, so t is finite).
  const float t = st > 0.0f ? -std::log1p(-u) / st : kInfinity;
  if (t < t_max) {
    s.t = t;
    s.scattered = true;
    s.pdf = free_flight_pdf(m, t);
    s.weight = s.pdf > 0.0f ? Rgb(transmittance(m, t) * m.sigma_s / s.pdf) : Rgb(Rgb::Zero());
  } else {
    s.t = t_max;
    s.pdf = free_flight_pass_probability(m, t_max);
    s.weight = s.pdf > 0.0f ? Rgb(transmittance(m, t_max) / s.pdf) : Rgb(Rgb::Zero());
  }
  return s;
}

}  // namespace dp::scene
