// GD-MLT's extended-path-space target (Manzi et al. 2014, Sec. 4; Lehtinen et al. 2013,
// Sec. 5) for path-space chains (`gdmlt --set mutations=path`): a state z = (x, j) is a
// full path x of pixel i (path_state.h) and one neighbour j of the pair set N_i of a
// kernels_adaptive::PairKernel, chosen by the coordinate u_pair (j = N_i[floor(u |N_i|)],
// redrawn uniformly at every proposal as in the primary-sample-space target,
// gradient_target.h). The target is
//   f(z) = |N_i| ||Delta^i_ij(x)|| + alpha ||F(x)||                    (Manzi 2014, Sec. 4)
// with Delta^i_ij the symmetric gradient sample of x and its shift T_1 x into pixel j
// (gradients/symmetric_gradient.h, Eqs. 4-6). Mutations only give ratios of F
// (path_state.h), so the chain samples lum F * factor with factor = f(z) / lum F
// (path_chain.h: PathTargetFactor).
//
// T_1 is G-BDPT's shift of full paths (gradients/bidir_shift.h: the camera end replayed
// through Dirac lobes to the first smooth vertex b, reconnected to x_{b+1} or rejoined at
// the end of a walked specular chain), one map for every strategy. The value
// F(T_1 x) |T_1'| is formed through the state's reference strategy s = ref (its first
// strategy with a non-zero contribution, the same for x and T_1 x: the shift keeps every
// vertex's lobe kind): the offset camera prefix (t = K + 1 - s vertices) connected to
// x's light prefix gives F(T_1 x) |T_1'| / p_s(x), where C_s(x) = F(x) / p_s(x) is the
// state's c_ref; the ratio of the two is F(T_1 x) |T_1'| / F(x) in any measure. Paths only
// light tracing samples (ref = K: t = 1) are not shifted: they are in Omega_bar (Eq. 4)
// for every pixel, a set the shift maps onto itself, so the pair integrals stay unbiased.
// Eq. 6's ratio compares F(x) / p_s(x) with F(T_1 x) / p_s(x) in strategy s's own
// coordinates (the Jacobian divided out: the reconnection's solid-angle factor when the
// prefix rejoined before its end, else 1), the same comparison from either side.
#pragma once

#include "gradients/bidir_shift.h"
#include "gradients/symmetric_gradient.h"
#include "kernels_adaptive/pair_kernel.h"
#include "mcmc/gradient_target.h"
#include "mcmc/path_chain.h"

namespace dp::mcmc {

struct PathGradientOptions {
  double alpha = 0.2;                        // weight of the primal term in f(z)
  gradients::SymmetricGradientOptions gradient;
  gradients::BidirShiftOptions shift;        // walk_chains: the manifold shift; fault: tests
  bool identity = false;                     // T_1 = identity: no offset (every x in Omega_bar)
};

class PathGradientFactor final : public PathTargetFactor {
 public:
  // `kernel` must match the camera's image size (dp::ValueError otherwise); shared read-only.
  PathGradientFactor(const scene::Scene& scene, const kernels_adaptive::PairKernel& kernel,
                     const PathGradientOptions& options);
  void evaluate(PathState& s) override;
  // cases and shift_status as the primary-sample-space target's (no INCMW here).
  const GradientTargetCounters& counters() const { return m_counters; }
  int64_t light_tracing_only() const { return m_light_tracing_only; }

 private:
  const scene::Scene& m_scene;
  const kernels_adaptive::PairKernel& m_kernel;
  PathGradientOptions m_opt;
  int m_w, m_h;
  PathSides m_sides;
  gradients::CameraSubpathShift m_shift;
  GradientTargetCounters m_counters;
  int64_t m_light_tracing_only = 0;
};

}  // namespace dp::mcmc
