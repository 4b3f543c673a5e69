// The primary-sample-space target of PSSMLT: coordinates 0 and 1 place the camera sample
// anywhere on the image (raster = (u0 W, u1 H)); the rest drive pathspace::PathBuilder
// (its coordinate layout). The splatted value C(u) is the path tracer's estimate of the
// walk (pt_contribution); f(u) = luminance(C(u)) (Kelemen et al. 2002 use luminance as
// the scalar importance). Since the raster sample's density is 1 / (W H) on the image,
// pixel j's value is W H * integral of h_j C du; integral of f du = b (bootstrap.h).
#pragma once

#include "mcmc/target.h"
#include "pathspace/path_builder.h"

namespace dp::mcmc {

// What the reference path tracer (integrators/path) adds up for one camera sample: for
// every vertex x_k, the NEE path (x_0..x_k, nee[k]) and the BSDF path ending at an
// emitting x_k, each weighted by the power heuristic over the two strategies
// (Veach 1997, Eq. 9.13, beta = 2); directly seen emitters and paths after a Dirac lobe
// or without NEE have weight 1, delta lights have NEE weight 1.
Rgb pt_contribution(const scene::Scene& scene, const pathspace::Path& path, bool nee);

class PathTarget final : public Target {
 public:
  PathTarget(const scene::Scene& scene, const pathspace::WalkOptions& options);
  TargetValue evaluate(pathspace::SampleStream& stream) override;
  const pathspace::Path& path() const { return m_path; }

 private:
  pathspace::PathBuilder m_builder;
  pathspace::Path m_path;
  float m_width, m_height;
};

}  // namespace dp::mcmc
