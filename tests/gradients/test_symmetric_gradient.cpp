// Manzi et al. 2014, Eqs. 4-6 (gradients/symmetric_gradient.h), checked on random pairs of
// a base path x (pixel i, density p_x) and its offset y = T(x) (pixel j, density p_y,
// |dy/dx| = J). Pixel i's sample s_i estimates part of I_i - I_j, pixel j's s_j part of
// I_j - I_i; per unit of x's measure the two give s_i p_x - s_j p_y J, which must equal the
// integrand of the gradient, f_i(x) - f_j(y) J, in every case (both sides succeed, Eq. 6
// fallback, one side zero), and both sides must choose the same case (the weights are
// evaluated symmetrically). Broken variants watched failing: the 1/2 of Eq. 4 dropped (the
// sum), and a one-sided Eq. 6 test f_i > t f_j instead of the max of both ratios (the
// cases differ). (The ratio may include the Jacobian or not: both are symmetric.)
#include <catch2/catch.hpp>
#include <cmath>

#include "core/rng.h"
#include "gradients/symmetric_gradient.h"

using namespace dp;

namespace {
struct Sides {
  gradients::GradientSample i, j;
  double combined;  // s_i p_x - s_j p_y J (luminance)
};

Sides both_sides(double fi, double fj, double J, double px, double py, const gradients::SymmetricGradientOptions& o) {
  const Rgbd Fi = Rgbd::Constant(fi), Fj = Rgbd::Constant(fj);
  Sides s;
  s.i = gradients::symmetric_gradient(Fi / px, Fj * J / px, true, J, o);
  s.j = gradients::symmetric_gradient(Fj / py, Fi / J / py, true, 1.0 / J, o);
  s.combined = s.i.value[0] * px - s.j.value[0] * py * J;
  return s;
}
}  // namespace

TEST_CASE("symmetric gradients: both pixels together integrate f_i - f_j J in every case of Eqs. 4-6", "[unit]") {
  core::Rng rng(7, 1);
  gradients::SymmetricGradientOptions o;  // MWGI on, t = 20
  int shifted = 0, fallback = 0;
  for (int n = 0; n < 20000; ++n) {
    // Log-uniform magnitudes so both sides of t = 20 occur often.
    const double fi = std::exp(6.0 * rng.uniform_double() - 3.0), fj = std::exp(6.0 * rng.uniform_double() - 3.0);
    const double J = std::exp(4.0 * rng.uniform_double() - 2.0);
    const double px = std::exp(2.0 * rng.uniform_double()), py = std::exp(2.0 * rng.uniform_double());
    const Sides s = both_sides(fi, fj, J, px, py, o);
    REQUIRE(s.i.kind == s.j.kind);
    REQUIRE(s.combined == Approx(fi - fj * J).epsilon(1e-12).margin(1e-12 * (fi + fj * J)));
    shifted += s.i.kind == gradients::GradientCase::shifted;
    fallback += s.i.kind == gradients::GradientCase::fallback;
  }
  REQUIRE(shifted > 1000);   // both cases were exercised
  REQUIRE(fallback > 1000);
}

TEST_CASE("symmetric gradients: a failed or zero offset is Omega_bar (base alone); t -> infinity never falls back",
          "[unit]") {
  gradients::SymmetricGradientOptions o;
  const Rgbd fb(0.3, 0.2, 0.1), fo(0.25, 0.2, 0.15);
  const auto failed = gradients::symmetric_gradient(fb, fo, false, 1.0, o);
  REQUIRE(failed.kind == gradients::GradientCase::omega_bar);
  REQUIRE((failed.value == fb).all());
  const auto zero = gradients::symmetric_gradient(fb, Rgbd::Zero(), true, 1.0, o);
  REQUIRE(zero.kind == gradients::GradientCase::omega_bar);
  REQUIRE((zero.value == fb).all());
  // Offset 1000x the base: Eq. 6 falls back at t = 20 but not at t = 1e300 (T_1 only).
  const auto far = gradients::symmetric_gradient(fb, 1000.0 * fb, true, 1.0, o);
  REQUIRE(far.kind == gradients::GradientCase::fallback);
  REQUIRE((far.value == fb).all());
  o.threshold = 1e300;
  const auto t1 = gradients::symmetric_gradient(fb, 1000.0 * fb, true, 1.0, o);
  REQUIRE(t1.kind == gradients::GradientCase::shifted);
  REQUIRE((t1.value == 0.5 * (fb - 1000.0 * fb)).all());
  o.mwgi = false;
  REQUIRE(gradients::symmetric_gradient(fb, 1000.0 * fb, true, 1.0, o).kind == gradients::GradientCase::shifted);
}
