#include "gradients/symmetric_gradient.h"

#include <cmath>

namespace dp::gradients {

double magnitude(const Rgbd& v) {
  return 0.212671 * std::abs(v[0]) + 0.715160 * std::abs(v[1]) + 0.072169 * std::abs(v[2]);
}

GradientSample symmetric_gradient(const Rgbd& fb, const Rgbd& fo, bool has_offset, double jacobian,
                                  const SymmetricGradientOptions& options) {
  GradientSample s;
  const double mb = magnitude(fb), mo = magnitude(fo);
  if (!has_offset || !(mo > 0.0) || !(mb > 0.0) || !(jacobian > 0.0)) {
    // Omega_bar_i (Eq. 4, first term); also T_0 with w_0 = 1 (Eq. 6, ratio infinite).
    s.value = fb;
    s.kind = GradientCase::omega_bar;
    return s;
  }
  // Eq. 6: ratio of the path contributions f_i(x) and f_j(T_1 x) = fo p(x) / |T_1'|.
  const double fi = mb, fj = mo / jacobian;
  if (options.mwgi && (fi > options.threshold * fj || fj > options.threshold * fi)) {
    s.value = fb;  // w_0 = 1: the identity's term, f_i(x) alone
    s.kind = GradientCase::fallback;
    return s;
  }
  s.value = 0.5 * (fb - fo);  // Eq. 4, second term (x in Omega_ij, w_1 = 1)
  s.kind = GradientCase::shifted;
  return s;
}

}  // namespace dp::gradients
