// Equiangular distance sampling (Kulla & Fajardo 2012, "Importance Sampling Techniques for
// Path Tracing in Participating Media", Sec. 4): a point on the ray segment o + t d,
// t in [0, t_max], drawn with density proportional to 1 / |x(t) - y|^2 for a light point y,
// i.e. uniformly in the angle subtended at y:
//   delta = (y - o).d, h = |y - (o + delta d)|, theta_a = atan(-delta / h),
//   theta_b = atan((t_max - delta) / h)   (pi / 2 for t_max = inf),
//   t(u)  = delta + h tan(theta_a + u (theta_b - theta_a)),
//   p(t)  = h / ((theta_b - theta_a) (h^2 + (t - delta)^2)).
// Free-flight sampling's density falls off with the transmittance only, so a medium point
// close to a small light is rarely drawn while its next-event estimate grows as 1 / r^2:
// the estimator's fireflies. This sampler cancels the 1 / r^2 of the geometry term.
// Degenerate (ok = false): y on the ray's line (h = 0), an empty segment, non-finite input.
#pragma once

#include "core/math.h"

namespace dp::scene {

struct Equiangular {
  double delta = 0, h = 0, theta_a = 0, theta_b = 0;
  bool ok = false;
};

Equiangular equiangular_setup(const Vec3& o, const Vec3& d, float t_max, const Vec3& y);
// u in [0, 1); the result lies in [0, t_max].
float equiangular_sample(const Equiangular& e, float t_max, float u);
// The density of t (0 outside [0, t_max]).
float equiangular_pdf(const Equiangular& e, float t_max, float t);

}  // namespace dp::scene
