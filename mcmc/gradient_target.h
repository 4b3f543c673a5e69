// The extended-path-space target of gradient-domain MLT (Manzi et al. 2014, Sec. 4), in
// primary sample space. A state z = (x, j): a path x in pixel i and one neighbour j of
// the pair set N_i of a kernels_adaptive::PairKernel (standard: the 4-neighbours inside
// the image; adaptive: the structure-adaptive pairs of Sec. 3.5).
// Coordinates: 0 chooses j = N_i[floor(u_0 |N_i|)] (the chain redraws it uniformly at
// every mutation: ChainOptions::redraw_first = 1, Manzi's "propose j uniformly"), 1-2
// place the camera sample on the whole image, the rest drive pathspace::PathBuilder.
// Per state: the primal value f*(x) = sum of the walk's concrete paths with >= 3
// segments (strategy weights as the reference PT; shorter paths are the direct pass's),
// the pair sample s = Delta^i_ij (gradients/symmetric_gradient.h, per concrete path,
// shifted with T_1 = the chosen Shift), and the target
//   f(z) = |N_i| ||s|| + alpha ||f*(x)||                           (Manzi 2014, Sec. 4)
// as a density on the unit cube of (u_0, u_1, ...). Splats: f* at pixel i, w |N_i| s into
// the kernel row of the entry (i -> j, row, w) (kernels_adaptive/pair_kernel.h: w = +-1,
// or 2 for a symmetric adaptive pair; Algorithm 1 line 13). Since j has measure
// 1/|N_i| in u_0, the integral of |N_i| s over the cube is the sum over j of the pair
// integrals, and the integral of f over the cube is the normalisation b.
#pragma once

#include <array>
#include <memory>

#include "gradients/pair_terms.h"
#include "gradients/shift.h"
#include "gradients/symmetric_gradient.h"
#include "kernels_adaptive/pair_kernel.h"
#include "manifold/walk_stats.h"
#include "mcmc/target.h"
#include "pathspace/path_builder.h"

namespace dp::mcmc {

struct GradientTargetOptions {
  pathspace::WalkOptions walk;
  double alpha = 0.2;  // weight of the primal term in f(z)
  gradients::SymmetricGradientOptions gradient;
  int min_segments = 3;  // shorter paths belong to the direct pass
};

// What one state did (for the integrator's JSON counters).
struct GradientTargetCounters {
  std::array<int64_t, 3> cases{};  // concrete paths by gradients::GradientCase
  std::array<int64_t, gradients::kShiftStatusCount> shift_status{};
  int64_t shifts = 0;
  int64_t incmw_shifts = 0;    // shifts in which INCMW declared vertices (Manzi 2014, Sec. 3.4)
  int64_t incmw_declared = 0;  // vertices declared in them
  manifold::WalkStats walks;
  void merge(const GradientTargetCounters& o);
};

class GradientTarget final : public Target {
 public:
  // `shift` and `kernel` are shared read-only between targets (Shift::shift is const);
  // the kernel must match the camera's image size (dp::ValueError otherwise).
  GradientTarget(const scene::Scene& scene, const gradients::Shift& shift, const kernels_adaptive::PairKernel& kernel,
                 const GradientTargetOptions& options);
  TargetValue evaluate(pathspace::SampleStream& stream) override;
  const GradientTargetCounters& counters() const { return m_counters; }

 private:
  const gradients::Shift& m_shift;
  const kernels_adaptive::PairKernel& m_kernel;
  GradientTargetOptions m_opt;
  pathspace::PathBuilder m_builder;
  gradients::PairTerms m_terms;
  pathspace::Path m_base;
  gradients::ShiftResult m_res;
  int m_w, m_h;
  GradientTargetCounters m_counters;
};

}  // namespace dp::mcmc
