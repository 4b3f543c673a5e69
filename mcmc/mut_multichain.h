// Veach's multi-chain perturbation (Veach 1997, Sec. 11.4.3; Mitsuba 0.6's mut_mchain.cpp,
// docs/memlt_plan.md Sec. 2.4): the lens perturbation for paths seen through two or more
// specular chains, E S* D S+ D ... S+ x_c x_{c-1} (a pool floor seen through a water
// surface): the raster moves as in the lens perturbation, the camera ray is re-traced
// through x's Dirac lobes to the first smooth vertex, where the direction onward turns by
// a small angle theta (log-uniform on [theta1, theta2] = [1e-4, 0.1] degrees, Mitsuba's)
// about x's own direction there, and so on through every chain to y_c, which connects to
// the kept x_{c-1}. The raster offset and each turn have densities that depend only on the
// offset and the angle (symmetric), so with C_c = F / p_c (path_state.h), the camera walk
// sampling the same directions with the BSDF densities p_w at the intermediate smooth
// vertices and the Dirac lobes' P_rad:
//   ratio = [C_c(y) prod p_w(y) prod P_rad(y)] / [C_c(x) prod p_w(x) prod P_rad(x)].
#pragma once

#include <vector>

#include "mcmc/mutator.h"

namespace dp::mcmc {

class MultiChainPerturbation final : public Mutator {
 public:
  // r1, r2: the lens perturbation's raster offsets (pixels).
  MultiChainPerturbation(const scene::Scene& scene, double r1, double r2);
  const char* name() const override { return "multichain"; }
  bool suitable(const PathState& x) const override;
  ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                        PathSides& sides) const override;
  double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const override;

 private:
  // The smooth vertices from the camera down to c (the last, whose lower neighbour is
  // smooth too): empty if the path is not E S* (D S+)+ D D .. with at least two of them.
  std::vector<int> smooth_ends(const PathState& x) const;
  const scene::Scene& m_scene;
  double m_r1, m_r2, m_theta1, m_theta2;
};

}  // namespace dp::mcmc
