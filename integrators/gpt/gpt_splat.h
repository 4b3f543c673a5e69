// The symmetric MIS-weighted splat of one pixel pair (i, j) of G-PT (Kettunen et al. 2015,
// Sec. 4; gradients/mis.h), shared by the surface tracer (GptTracer) and the tracer in
// media (GptMediaTracer): every concrete path of the pair (gradients::PairTerm: base
// value fb, offset value fo in the base's measure, density ratios b_other, c, d) adds
//   primal_i += w fb,   primal_j += w fo,   gradient(i -> j) += w (fo - fb)
// (a failed shift leaves only -w fb in the gradient; a neighbour outside the image has no
// offset terms), then each pixel's primal gets 1/4 of its pair estimates and the gradient
// is stored as the forward difference dx / dy.
#pragma once

#include <cstdint>

#include "gradients/gradient_buffers.h"
#include "gradients/mis.h"
#include "gradients/pair_terms.h"
#include "integrators/gpt/gpt_settings.h"

namespace dp::integrators {

// Neighbour offsets of the four pairs, in the order every G-PT tracer visits them.
inline constexpr int kGptDx[4] = {1, -1, 0, 0}, kGptDy[4] = {0, 0, 1, -1};

// The symmetric power-heuristic weight (gradients/mis.h), or the MisFault defect of a
// tests' negative control (one predictable branch).
inline double gpt_mis_weight(double other_base, double offset_same, double offset_other, MisFault fault) {
  if (fault == MisFault::without_offset) [[unlikely]]
    return gradients::symmetric_power_weight(other_base, 0.0, 0.0);
  return gradients::symmetric_power_weight(other_base, offset_same, offset_other);
}

// Splats the terms of pair (px, py) -> neighbour nb into `buf`; `inside`: the neighbour
// is in the image. Returns false (nothing splatted) if a sum is not finite.
template <class Terms>
bool splat_gpt_pair(const Terms& terms, int px, int py, int nb, bool inside, MisFault fault,
                    gradients::GradientBuffers& buf) {
  Rgbd primal_i = Rgbd::Zero(), primal_j = Rgbd::Zero(), grad = Rgbd::Zero();
  for (const gradients::PairTerm& t : terms) {
    const double wgt = gpt_mis_weight(t.b_other, t.c, t.d, fault);
    primal_i += wgt * t.fb;
    if (t.has_offset) {
      primal_j += wgt * t.fo;
      grad += wgt * (t.fo - t.fb);
    } else if (inside) {
      grad -= wgt * t.fb;
    }
  }
  if (!primal_i.isFinite().all() || !primal_j.isFinite().all() || !grad.isFinite().all()) return false;
  buf.add_primal(px, py, 0.25 * primal_i);
  if (!inside) return true;
  const int qx = px + kGptDx[nb], qy = py + kGptDy[nb];
  buf.add_primal(qx, qy, 0.25 * primal_j);
  // grad estimates I_j - I_i; the buffers hold forward differences.
  if (kGptDx[nb] == 1) buf.add_dx(px, py, grad);
  else if (kGptDx[nb] == -1) buf.add_dx(qx, qy, -grad);
  else if (kGptDy[nb] == 1) buf.add_dy(px, py, grad);
  else buf.add_dy(qx, qy, -grad);
  return true;
}

}  // namespace dp::integrators
