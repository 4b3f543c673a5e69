// Veach's lens perturbation (Veach 1997, Sec. 11.4.3; Mitsuba 0.6's mut_lens.cpp,
// docs/memlt_plan.md Sec. 2.2). For a path ending ... x_{c-1} x_c S* E (x_{c-1} and x_c
// smooth, S* Dirac vertices seen through by the camera): the raster position moves by
// r (cos phi, sin phi), r log-uniform on [r1, r2] (r1 = 0.1 pixel, r2 covering
// `area_fraction` of the image: sqrt(f W H / pi)), phi uniform; the new camera ray is
// traced through x's Dirac lobes to y_c, which is connected to the kept x_{c-1}. A raster
// outside the image fails (a rejection).
// The raster density g(|offset|) is symmetric. The camera walk's density of y_c is
// J_y / (W H) * prod P_rad (J: raster per area at y_c through the chain; P the Dirac lobes'
// probabilities), the perturbation's g J_y, so with C_c = F / p_c (path_state.h)
//   ratio = [C_c(y) prod P_rad(y)] / [C_c(x) prod P_rad(x)]
// (lum of C; the light prefix's density is the same in both).
#pragma once

#include "mcmc/mutator.h"

namespace dp::mcmc {

struct LensSettings {
  double r1 = 0.1;              // pixels
  double area_fraction = 0.05;  // r2 = sqrt(area_fraction W H / pi) (Veach, p. 354)
};

class LensPerturbation final : public Mutator {
 public:
  LensPerturbation(const scene::Scene& scene, const LensSettings& settings = {});
  const char* name() const override { return "lens"; }
  bool suitable(const PathState& x) const override;
  ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                        PathSides& sides) const override;
  double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const override;
  double r1() const { return m_r1; }
  double r2() const { return m_r2; }

 private:
  const scene::Scene& m_scene;
  double m_r1, m_r2;
};

}  // namespace dp::mcmc
