// The manifold perturbation of manifold exploration Metropolis light transport (Jakob &
// Marschner 2012, Sec. 5; Mitsuba 0.6's mut_manifold.cpp, docs/memlt_plan.md Sec. 2.5),
// for specular chains of Dirac vertices (glossy vertices count as smooth here; Mitsuba's
// "glossy treated as specular" with its half-vector determinant is not built):
//  1. (a, step): with probability `sensor_prob` the pinhole and step -1 (if that start
//     is valid), else uniform over the valid starts: a a smooth vertex that can scatter or
//     emit (surface, finite light, pinhole), b = the first smooth vertex after a in that
//     direction (a surface), c = the next one (a surface or an area light the chain can
//     be pinned to). Mitsuba draws a and step blindly and retries; the explicit pmf over
//     the valid starts spends no proposal on an impossible one.
//  2. The direction leaving x_a toward b turns by a vMF sample about the old one whose
//     peak density is lambda^2 max(1/(4 pi), p(w_old)) (p: the walk's density of the old
//     direction on the path being perturbed; lambda = 50).
//  3. a -> b is re-traced through x's Dirac lobes (perturb_chain.h); the specular chain
//     b .. c (if any) is re-solved by a manifold walk with c pinned and b moved
//     (gradients/bidir_chain.h: walk_exact, reversibility checked); else b connects to c.
// Density ratio: a walk strategy s that generates a .. c in the perturbation's direction
// (camera walk, s <= c, for step -1; light walk, s - 1 >= c, for step +1) samples b with
// density p_w(a) prod P(a..b) J_ab and c with p_w(b) prod P(b..c) J_bc (J_uv = d w_u /
// dA_v through the chain, G(u, v)/|cos_u|), the vertex after c with p_w(c); the
// perturbation samples b with p_vMF(w) J_ab. With C_s = F/p_s (path_state.h) J_ab cancels:
//   ratio = [C_s(y) D(y) p_vMF(w_x; kappa_y) P(a, step; y)] / [C_s(x) D(x) p_vMF(w_y; kappa_x) P(a, step; x)]
//           * J_bc(y) / J_bc(x),   D = p_w(a) prod P(a..b) p_w(b) prod P(b..c) [p_w(c)].
#pragma once

#include "gradients/bidir_chain.h"
#include "mcmc/mutator.h"

namespace dp::mcmc {

struct ManifoldSettings {
  double lambda = 50;         // vMF peak factor (Jakob & Marschner 2012; Mitsuba's probFactor)
  double sensor_prob = 0.25;  // start at the pinhole when x_{K-1} is smooth (Mitsuba's SENSOR_PROB)
  manifold::WalkSettings walk;
};

class ManifoldPerturbation final : public Mutator {
 public:
  ManifoldPerturbation(const scene::Scene& scene, const ManifoldSettings& settings = {});
  const char* name() const override { return "manifold"; }
  bool suitable(const PathState& x) const override { return x.depth() >= 2; }
  ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                        PathSides& sides) const override;
  double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const override;

  // Probability of choosing (a, step) on s.
  double start_pmf(const PathState& s, int a, int step) const;

 private:
  bool eligible_start(const PathState& s, int i) const;
  // a can start in direction step: b (a surface) and c (pinnable: a surface or an area light
  // past a chain; any smooth vertex but the pinhole or a light at infinity next to b) exist.
  bool valid_start(const PathState& s, int a, int step, int& b, int& c) const;
  // Walk density of leaving vertex i of s toward i + step (arriving from i - step).
  double leave_density(const PathState& s, int i, int step) const;
  double kappa(const PathState& s, int a, int step) const;

  const scene::Scene& m_scene;
  ManifoldSettings m_opt;
};

}  // namespace dp::mcmc
