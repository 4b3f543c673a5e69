// The manifold shift (gradients/manifold_shift.h) on real scenes with mirror and glass
// spheres: (1) its Jacobian vs the determinant of central finite differences of the
// shift map in the same parameterization (solid angle of the direction sampled at b ->
// that of the offset at b'): the base chain is re-traced from b in double along the
// perturbed direction to a new c, the offset chain is walked from that c to b' to a tight
// tolerance, and the offset's direction at b' is read off; relative error <= 1e-4 for
// every case, distribution printed, and a wrong formula (the cosine ratio forgotten) is
// caught; (2) bijectivity T^-1(T(x)) = x with J(x) J^-1(T(x)) = 1, manifold steps
// included; (3) strategy selection: chains that are not purely specular, or paths cut
// inside a chain, keep the reconnection shift's steps exactly.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "gradients/manifold_shift.h"
#include "manifold/constraints.h"
#include "pathspace/path_builder.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/loaders/loader.h"
#include "tests/support/test_scenes.h"
#include "tests/support/direction_chart.h"

using namespace dp;
using gradients::StepKind;

namespace {
scene::BsdfPtr mirror() { return scene::make_mirror(scene::constant_texture(Rgb::Constant(0.9f))); }
scene::BsdfPtr glass() { return scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx); }

using Chart = test::DirectionChart;
}  // namespace

namespace dp::test {
// Per-sample first-order bound on |J(x) J^-1(T(x)) - 1| (derivation at its definition in
// test_bijectivity.cpp: measured vertex displacements and float rounding over segment
// length and cosines, times the curvature gain of Dirac vertices). The manifold walks'
// convergence tolerance (1e-7 x scale) enters through the measured |x' - x|.
double jj_tolerance(const pathspace::Path& x, const pathspace::Path& x_back, int n);
}  // namespace dp::test

namespace {

manifold::Chain reversed(const manifold::Chain& c) {
  manifold::Chain r = c;
  std::reverse(r.v.begin(), r.v.end());
  return r;
}

struct Report {
  std::vector<double> err;
  void add(double e) { err.push_back(e); }
  double quantile(double f) const {
    std::vector<double> e = err;
    std::sort(e.begin(), e.end());
    return e[std::min(e.size() - 1, size_t(f * double(e.size())))];
  }
  void print(const char* name) const {
    std::printf("manifold shift jacobian %-14s n=%zu  median %.2e  p90 %.2e  p99 %.2e  max %.2e\n", name, err.size(),
                quantile(0.5), quantile(0.9), quantile(0.99), quantile(1.0));
  }
};

// Base walks in pixel i and their forward shifts in pixel i+1 (k: the chain's start b,
// m its end c): every successful manifold step, or with `attempted` every walked chain.
template <class F>
void for_each_manifold_step(const scene::Scene& s, const gradients::ManifoldShift& shift, int samples, uint64_t seed,
                            F&& fn, bool attempted = false) {
  pathspace::WalkOptions wo;
  wo.max_depth = 8;
  wo.shift_threshold = shift.options().threshold;
  const pathspace::PathBuilder builder(s, wo);
  core::Rng rng(seed, 3);
  pathspace::IndependentStream stream(rng);
  pathspace::Path x;
  gradients::ShiftResult fwd;
  const int res = s.camera().width();
  for (int i = 0; i < samples; ++i) {
    builder.build(i % (res - 1), (i / (res - 1)) % res, stream, x);
    shift.shift(x, Vec2(1, 0), fwd);
    for (int k = 1; k + 1 < (attempted ? x.size() : fwd.alive); ++k)
      if (fwd.step[size_t(k)] == StepKind::manifold) {
        int m = k + 1;
        while (m < x.size() && !x[m].connectable) ++m;
        fn(x, fwd, k, m);
        break;
      }
  }
}
}  // namespace

TEST_CASE("manifold shift Jacobian vs finite differences of the shift map (mirror and glass chains)", "[unit]") {
  const auto s = test::lit_box(mirror(), glass(), 24);
  gradients::ManifoldShiftOptions opt;
  opt.reconnection.threshold = 0.001f;
  opt.emitter_chains_only = false;  // every chain ending on a connectable vertex
  const gradients::ManifoldShift shift(*s, opt);
  manifold::WalkSettings tight;
  tight.tolerance = 1e-13;
  tight.max_iterations = 60;
  tight.min_step = 1e-6;
  Report rep, wrong, refl, refr;
  int tried = 0;
  for_each_manifold_step(*s, shift, 20000, 21, [&](const pathspace::Path& x, const gradients::ShiftResult& r, int k,
                                                    int m) {
    ++tried;
    const auto chain_c = shift.make_chain(x, k, m);
    REQUIRE(chain_c);
    // The base chain from b, re-traced in double along its own first segment.
    const manifold::Chain from_b = reversed(*chain_c);
    manifold::Chain exact;
    if (manifold::retrace(*s, from_b, from_b.v[1].p(), exact) != manifold::WalkStatus::ok) return;
    const Vec3d b = exact.v[0].p(), b_off = r.path[k].p().cast<double>();
    const double d1 = (exact.v[1].p() - b).norm();
    const Chart in(exact.v[1].p() - b);
    // The shift map w_b -> w'_b' (false if the perturbed chain leaves its surfaces).
    auto map = [&](const Vec3d& w, Vec3d& w_off) {
      manifold::Chain c;
      if (manifold::retrace(*s, from_b, b + d1 * w, c) != manifold::WalkStatus::ok) return false;
      const manifold::WalkResult wr = manifold::walk(*s, reversed(c), b_off, tight);
      if (!wr.ok()) return false;
      const int n = wr.chain.n();
      w_off = (wr.chain.v[size_t(n - 1)].p() - wr.chain.v[size_t(n)].p()).normalized();
      return true;
    };
    Vec3d w0_off;
    if (!map(in.w, w0_off)) return;
    const Chart out(w0_off);
    // Central differences with Richardson extrapolation (h, h/2: the O(h^2) term cancels;
    // near caustic folds the map is strongly curved).
    auto diff = [&](double h, Eigen::Matrix2d& D) {
      for (int c = 0; c < 2; ++c) {
        Vec3d wp, wm;
        if (!map(in.at(c == 0 ? h : 0, c == 1 ? h : 0), wp) || !map(in.at(c == 0 ? -h : 0, c == 1 ? -h : 0), wm))
          return false;
        D.col(c) = (out.coords(wp) - out.coords(wm)) / (2 * h);
      }
      return true;
    };
    auto fd_at = [&](double h) {
      Eigen::Matrix2d D1, D2;
      if (!diff(h, D1) || !diff(h / 2, D2)) return std::nan("");
      return std::abs(((4.0 * D2 - D1) / 3.0).determinant());
    };
    const double fd = fd_at(4e-6);
    if (!(fd > 1e-3) || !(fd < 1e3)) return;
    const double J = r.jacobian[size_t(k)];
    const double e = std::abs(J - fd) / fd;
    rep.add(e);
    bool any_refraction = false;
    for (int j = 1; j < chain_c->n(); ++j) any_refraction |= chain_c->v[size_t(j)].type == manifold::Interaction::refraction;
    (any_refraction ? refr : refl).add(e);
    // Negative control: the generalized geometry ratio without the cosines at b and b'.
    double G0 = 0, G1 = 0;
    manifold::generalized_geometry(*chain_c, G0);
    manifold::generalized_geometry(reversed(exact), G1);
    const auto wr = manifold::walk(*s, reversed(exact), b_off, tight);
    if (wr.ok() && manifold::generalized_geometry(wr.chain, G1) == manifold::WalkStatus::ok)
      wrong.add(std::abs(G1 / G0 - fd) / fd);
  });
  rep.print("all");
  refl.print("mirror only");
  refr.print("with glass");
  std::printf("manifold shift jacobian: %d manifold steps tried, %zu compared; without the cosine ratio: median %.2e\n",
              tried, rep.err.size(), wrong.quantile(0.5));
  REQUIRE(refl.err.size() > 30);
  REQUIRE(refr.err.size() > 30);
  REQUIRE(rep.quantile(1.0) <= 1e-4);
  REQUIRE(wrong.err.size() > 30);
  REQUIRE(wrong.quantile(0.5) > 1e-2);  // a wrong formula is caught
}

TEST_CASE("manifold shift bijectivity T^-1(T(x)) = x through specular chains", "[unit]") {
  struct Case {
    const char* name;
    scene::BsdfPtr a, b;
  };
  const Case cases[] = {{"mirror", mirror(), nullptr}, {"glass", glass(), nullptr}, {"mirror+glass", mirror(), glass()}};
  // Both strategies: walk every eligible chain, or only where the half-vector copy leaves
  // the chain's shapes (fewer walks: more samples for the same coverage).
  for (const bool fallback : {false, true})
  for (const auto& cs : cases) {
    const auto s = test::lit_box(cs.a, cs.b, 24);
    gradients::ManifoldShiftOptions opt;
    opt.reconnection.threshold = 0.001f;
    opt.walk.check_reversible = true;  // --paranoid
    opt.emitter_chains_only = false;
    opt.walk_as_fallback = fallback;
    const gradients::ManifoldShift shift(*s, opt);
    int checked = 0, reverse_ok = 0, walk_fail = 0, newton_fail = 0, other_fail = 0;
    double worst_pos = 0, worst_jac = 0, worst_ratio = 0;
    int jj_over = 0;
    pathspace::Path y;
    gradients::ShiftResult rev;
    // Every successful forward shift (with or without a manifold step) must come back.
    pathspace::WalkOptions wo;
    wo.max_depth = 8;
    wo.shift_threshold = 0.001f;
    const pathspace::PathBuilder builder(*s, wo);
    core::Rng rng(31, 3);
    pathspace::IndependentStream stream(rng);
    pathspace::Path x;
    gradients::ShiftResult fwd;
    int with_manifold = 0;
    for (int i = 0; i < (fallback ? 24000 : 6000); ++i) {
      builder.build(i % 23, (i / 23) % 24, stream, x);
      shift.shift(x, Vec2(1, 0), fwd);
      if (fwd.walk_status > 0) ++walk_fail;
      if (fwd.alive < 2) continue;
      y = fwd.path;
      y.vertices.resize(size_t(fwd.alive));
      y.nee.resize(size_t(fwd.alive));
      for (int k = 0; k < fwd.alive; ++k)
        if (!fwd.nee_ok(k) || !(y.nee[size_t(k)].pdf > 0.0)) y.nee[size_t(k)].valid = false;
      shift.shift(y, Vec2(-1, 0), rev);
      ++checked;
      bool manifold_used = false;
      for (int k = 0; k + 1 < fwd.alive; ++k) manifold_used |= fwd.step[size_t(k)] == StepKind::manifold;
      with_manifold += manifold_used && fwd.walk_status == 0;
      // A pair is one-sided if the reverse fails or picks another strategy. The forward
      // shift runs the reverse's decisions itself (its walks, and with walk_as_fallback
      // its copies) on inputs that differ from the reverse's own only by float round-off,
      // so a flip needs a decision exactly at its edge (Newton's basin: step_too_small /
      // max_iterations; a copy grazing a shape's boundary): counted by kind. None occur
      // here; 6 in 24000 did while a partial copy (failing after passing a connectable
      // vertex the base's chain did not have) skipped the reverse-walk check.
      bool same = rev.alive == y.size();
      for (int k = 0; same && k + 1 < y.size(); ++k) same = rev.step[size_t(k)] == fwd.step[size_t(k)];
      if (!same) {
        auto newton = [](int st) {
          return st == int(manifold::WalkStatus::step_too_small) || st == int(manifold::WalkStatus::max_iterations);
        };
        (newton(rev.walk_status) || newton(fwd.walk_status) ? newton_fail : other_fail) += 1;
        continue;
      }
      ++reverse_ok;
      for (int k = 0; k < y.size(); ++k) worst_pos = std::max(worst_pos, double((rev.path[k].p() - x[k].p()).norm()));
      const double jj = std::abs(fwd.prefix_jacobian(y.size() - 1) * rev.prefix_jacobian(y.size() - 1) - 1.0);
      const double bound = test::jj_tolerance(x, rev.path, y.size());
      worst_jac = std::max(worst_jac, jj);
      worst_ratio = std::max(worst_ratio, jj / bound);
      jj_over += !(jj <= bound);
    }
    std::printf("manifold bijectivity %-8s %-12s checked %d reverse-ok %d (one-sided: at a Newton basin edge %d, other %d; "
                "with a manifold walk %d; forward walks failed %d)  worst |dx| %.2e  worst |J J^-1 - 1| %.2e (%d beyond "
                "the bound, worst %.2f of it)\n",
                fallback ? "fallback" : "always", cs.name, checked, reverse_ok, newton_fail, other_fail, with_manifold,
                walk_fail, worst_pos, worst_jac, jj_over, worst_ratio);
    INFO(cs.name << (fallback ? " fallback" : " always"));
    REQUIRE(with_manifold > 100);
    REQUIRE(newton_fail + other_fail == 0);
    REQUIRE(reverse_ok == checked);
    REQUIRE(worst_pos < 2e-3);
    // Each sample within its own bound (was: at most 1 % of the walked pairs beyond 1e-3
    // and all below 0.05, observed worst 2.5e-3: a 1 % Jacobian error passed). Near caustic
    // folds the bound grows with the chain's curvature gain instead of a blanket 5 %.
    // Detects a Jacobian off by 1 + 1e-4 in one direction on the pairs with a walk (seen
    // failing: 21 mirror pairs beyond their bound).
    REQUIRE(jj_over == 0);
  }
}

TEST_CASE("manifold shift keeps the reconnection shift's steps where no walk applies", "[unit]") {
  // A glossy sphere below the threshold and a diffuse one: chains are glossy, not purely
  // specular, so every step must equal ReconnectionShift's bit for bit; in the mirror box
  // the shifts differ exactly on paths with a walked chain (walked where the half-vector
  // copy leaves the chain's shapes) and where a copy is refused because its reverse would
  // walk; with the default (emitter_chains_only) only chains ending on the light are walked.
  const auto glossy = scene::make_two_sided(
      scene::make_conductor(0.05f, 0.05f, scene::MicrofacetType::ggx, scene::ConductorFresnel{}));
  struct Case {
    const char* name;
    scene::BsdfPtr a;
    float threshold;
    bool expect_walks, emitter_only;
  };
  const Case cases[] = {{"glossy", glossy, 0.1f, false, false},
                        {"mirror", mirror(), 0.001f, true, false},
                        {"cornell, emitter chains", nullptr, 0.05f, true, true}};
  for (const auto& cs : cases) {
    // The emitter-chain case needs caustics onto a light: the mirror+glass Cornell box.
    const auto s = cs.emitter_only ? scene::load_scene(std::string(DP_SOURCE_DIR) + "/scenes/cornell_specular.yaml")
                                   : test::lit_box(cs.a, nullptr, 16);
    gradients::ManifoldShiftOptions opt;
    opt.reconnection.threshold = cs.threshold;
    opt.emitter_chains_only = cs.emitter_only;
    const gradients::ManifoldShift ms(*s, opt);
    const gradients::ReconnectionShift rs(*s, opt.reconnection);
    pathspace::WalkOptions wo;
    wo.shift_threshold = cs.threshold;
    const pathspace::PathBuilder builder(*s, wo);
    core::Rng rng(41, 1);
    pathspace::IndependentStream stream(rng);
    pathspace::Path x;
    gradients::ShiftResult a, b;
    int walked = 0, identical = 0, total = 0, chain_ends_lit = 0, reverse_would_walk = 0;
    const int res = s->camera().width(), samples = cs.emitter_only ? 200000 : 6000;
    for (int i = 0; i < samples; ++i) {
      builder.build(i % (res - 1), (i / (res - 1)) % res, stream, x);
      ms.shift(x, Vec2(1, 0), a);
      rs.shift(x, Vec2(1, 0), b);
      ++total;
      int m = -1;  // a walked chain's end: the first connectable vertex after the chain
      for (int k = 1; k + 1 < a.alive && m < 0; ++k)
        if (a.step[size_t(k)] == StepKind::manifold)
          for (int j = k + 1; j < x.size() && m < 0; ++j)
            if (x[j].connectable) m = j;
      if (m > 0) {
        ++walked;
        if (cs.emitter_only) chain_ends_lit += x[m].hit.emitter != nullptr;
        continue;
      }
      bool same = a.alive == b.alive && a.status == b.status;
      for (int k = 0; same && k < a.alive; ++k)
        same = a.path[k].p() == b.path[k].p() && a.jacobian[size_t(k)] == b.jacobian[size_t(k)] &&
               a.nee_jacobian[size_t(k)] == b.nee_jacobian[size_t(k)] && a.step[size_t(k)] == b.step[size_t(k)];
      identical += same;
      // The one other difference: the copy's own chain is walk-eligible (it drifted onto
      // the light) and the reverse shift would walk it, so the copy is not invertible.
      const int k = a.alive - 1;
      reverse_would_walk += !same && a.status == gradients::ShiftStatus::not_invertible && b.alive > k + 1 &&
                            ms.chain_end(b.path, k, x[k]) >= 0;
    }
    std::printf("manifold vs reconnection %-22s: %d paths, %d with a walk, %d of the others identical, %d not "
                "invertible because the reverse shift would walk\n",
                cs.name, total, walked, identical, reverse_would_walk);
    INFO(cs.name);
    REQUIRE(identical + reverse_would_walk == total - walked);
    if (cs.emitter_only) {
      REQUIRE(walked > 10);
      REQUIRE(chain_ends_lit == walked);  // only chains ending on the light are walked
    } else if (cs.expect_walks) {
      REQUIRE(walked > 100);
    } else {
      REQUIRE(walked == 0);
    }
  }
}

TEST_CASE("manifold shift at Cornell-box scale: base chains re-trace onto their own vertices, shifts invert",
          "[unit]") {
  // Coordinates of hundreds of units (scenes/cornell_specular.yaml, 556 wide): a ray
  // offset that scales with |p| twice once put re-traced chains units off their paths.
  const auto s = scene::load_scene(std::string(DP_SOURCE_DIR) + "/scenes/cornell_specular.yaml");
  gradients::ManifoldShiftOptions opt;
  opt.reconnection.threshold = 0.05f;
  opt.emitter_chains_only = false;
  const gradients::ManifoldShift shift(*s, opt);
  const double tol = 1e-4 * double(s->scene_radius());
  int chains = 0, off = 0, walked = 0, reverse_ok = 0, jj_over = 0;
  double worst = 0, worst_jj = 0, worst_ratio = 0;
  pathspace::Path y;
  gradients::ShiftResult rev;
  for_each_manifold_step(*s, shift, 40000, 51, [&](const pathspace::Path& x, const gradients::ShiftResult& r, int k,
                                                    int m) {
    const auto chain = shift.make_chain(x, k, m);
    REQUIRE(chain);
    manifold::Chain from_b = reversed(*chain), exact;
    if (manifold::retrace(*s, from_b, x[k + 1].p().cast<double>(), exact) != manifold::WalkStatus::ok) return;
    ++chains;
    for (int j = k + 1; j <= m; ++j) {
      const double d = (exact.v[size_t(j - k)].p() - x[j].p().cast<double>()).norm();
      worst = std::max(worst, d);
      off += d > tol;
    }
    if (r.walk_status != 0 || r.alive <= m) return;
    ++walked;
    y = r.path;
    y.vertices.resize(size_t(r.alive));
    y.nee.resize(size_t(r.alive));
    for (auto& l : y.nee) l.valid = false;
    shift.shift(y, Vec2(-1, 0), rev);
    if (rev.alive != y.size() || !((rev.path[m].p() - x[m].p()).norm() < 1e-3f)) return;
    ++reverse_ok;
    // Near caustic folds G is ill-conditioned: float-level differences between the base
    // and the offset's re-traced chains show in J J^-1; the per-sample bound carries the
    // chain's curvature gain (the whole path's bound covers this one factor).
    const double jj = std::abs(r.jacobian[size_t(k)] * rev.jacobian[size_t(k)] - 1.0);
    const double bound = test::jj_tolerance(x, rev.path, y.size());
    worst_jj = std::max(worst_jj, jj);
    worst_ratio = std::max(worst_ratio, jj / bound);
    jj_over += !(jj <= bound);
  }, true);
  // Every chain a walk was attempted on (also the failed ones: a wrong re-trace makes
  // walks fail, which would hide it from a test of successful shifts only).
  std::printf("cornell-scale chains: %d re-traced, %d vertices off by > %.2g (worst %.2e); %d walked, %d inverted; "
              "|J J^-1 - 1| beyond its bound for %d (worst %.2e, %.2g of its bound)\n",
              chains, off, tol, worst, walked, reverse_ok, jj_over, worst_jj, worst_ratio);
  REQUIRE(chains > 100);
  REQUIRE(off == 0);
  REQUIRE(walked > 100);
  REQUIRE(reverse_ok == walked);  // the forward shift runs the reverse walk itself
  // Was: at most 1 % beyond 1e-3 and all below 0.05 (observed worst 1.5e-5). The bound is
  // loose at this scale (worst 0.004 of it), yet a walked step's Jacobian off by 1 + 1e-3
  // in one direction is caught (seen failing: 32 of 139 beyond their bound).
  REQUIRE(jj_over == 0);
}
