// Symmetric gradient samples with multiple weighted gradient integrals (Manzi et al.
// 2014, Sec. 3.2-3.3). For a base path x of pixel i and its shift T_1(x) into pixel j,
// the sample of pixel i's half of the gradient, Delta^i_ij (an estimate of a part of
// I_i - I_j; pixel j's samples give Delta^j_ij, and Delta_ij = Delta^i_ij + Delta^j_ij):
//   Eq. 4:  x in Omega_bar_i (T_1 failed, is not invertible, or f_j(T_1 x) = 0):  f_i(x)
//           x in Omega_ij:  1/2 (f_i(x) - f_j(T_1 x) |T_1'|)   (both pixels sample the pair)
// Eq. 6 (MWGI) mixes in the identity T_0, for which every x is in Omega_bar_i (the box
// filter puts T_0 x outside pixel j) with the binary weight
//   w_0(x) = 1 if max(||f_i(x)|| / ||f_j(T_1 x)||, ||f_j(T_1 x)|| / ||f_i(x)||) > t, else 0,
// w_1 = 1 - w_0. The ratio is the same seen from T_1 x (its shift back is x), so the
// weights are evaluated symmetrically, and Omega_bar_i has w_0 = 1 (ratio infinite):
//   sample = w_0 f_i(x) + w_1 1/2 (f_i(x) - f_j(T_1 x) |T_1'|).
// All values are per concrete path and already divided by the base density p(x) and
// multiplied by the strategy (NEE/BSDF) weights of the path and of its offset; `jacobian`
// turns the offset's value back into f_j(T_1 x) for the ratio (Eq. 6 compares path
// contributions, not Jacobian-weighted ones). ||.|| is the luminance of |RGB|.
#pragma once

#include "core/math.h"

namespace dp::gradients {

struct SymmetricGradientOptions {
  bool mwgi = true;        // Eq. 6 fallback to T_0; false: T_1 only (Eq. 4 alone)
  double threshold = 20;   // t of Eq. 6 (Manzi et al. 2014, Sec. 5: 20 in all scenes)
};

enum class GradientCase : uint8_t { omega_bar, shifted, fallback };  // T_1 failed/zero, T_1 used, T_0 by Eq. 6

struct GradientSample {
  Rgbd value = Rgbd::Zero();  // sample of Delta^i_ij (part of I_i - I_j)
  GradientCase kind = GradientCase::omega_bar;
};

// fb = w_s(x) f_i(x) / p(x); fo = w_s(T x) f_j(T x) |T'| / p(x) (0 if the shift failed);
// has_offset: the shift succeeded (invertibly) for this concrete path.
GradientSample symmetric_gradient(const Rgbd& fb, const Rgbd& fo, bool has_offset, double jacobian,
                                  const SymmetricGradientOptions& options);

// ||v||: luminance of the channel magnitudes (the scalar the targets and Eq. 6 use).
double magnitude(const Rgbd& v);

}  // namespace dp::gradients
