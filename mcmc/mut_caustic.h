// Veach's caustic perturbation (Veach 1997, Sec. 11.4.3; Mitsuba 0.6's mut_caustic.cpp,
// docs/memlt_plan.md Sec. 2.3). For a path ending ... x_l S* x_{K-1} E (x_l smooth or a
// finite light, S* Dirac vertices, x_{K-1} smooth): the direction leaving x_l toward the
// camera turns by theta about the old one (theta log-uniform on [theta1, theta2], phi
// uniform), the chain is re-traced through x's Dirac lobes to y_{K-1}, which is connected
// to the pinhole (the pixel moves). theta1,2 = (radians per pixel) * (r1, r2 of the lens
// perturbation) * |x_{K-1} x_K| / sum_{i=l}^{K-2} |x_i x_{i+1}| (Veach, p. 354), from the
// path being perturbed, so the range differs between x and y: its log-width ln(r2/r1) is
// the same, so p(theta) below cancels whenever theta lies in both ranges, and the reverse
// is impossible (ratio 0) when it does not.
// With the solid-angle density p(theta) = 1 / (2 pi ln(theta2/theta1) theta sin theta)
// and the light walk's density of the chain (the BSDF or emission density p_w at x_l
// times the Dirac lobes' P_imp), with C_K = F / p_K (light tracing, path_state.h):
//   ratio = [C_K(y) p_w(y) prod P_imp(y) p(theta; y)] / [C_K(x) p_w(x) prod P_imp(x) p(theta; x)].
#pragma once

#include "mcmc/mutator.h"

namespace dp::mcmc {

class CausticPerturbation final : public Mutator {
 public:
  CausticPerturbation(const scene::Scene& scene, double r1, double r2);
  const char* name() const override { return "caustic"; }
  bool suitable(const PathState& x) const override;
  ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                        PathSides& sides) const override;
  double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const override;
  // The angle range [theta1, theta2] on path s perturbed after vertex l.
  void angle_range(const PathState& s, int l, double& theta1, double& theta2) const;

 private:
  int kept_end(const PathState& x) const;  // l, or -1
  const scene::Scene& m_scene;
  double m_r1, m_r2, m_rad_per_pixel;
};

}  // namespace dp::mcmc
