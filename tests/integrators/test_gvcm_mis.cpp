// G-VCM's gradient MIS sums to one over the active and passive strategies (Sun et al.
// 2017, Eq. 21-23). For a base path x sampled by connect() and its shift T x into the +x
// neighbour, every strategy r that can generate x -- each connection split (light tracing
// included) and each merge at an interior non-Dirac vertex -- has in the tracer the
// gradient weight w_i,r = 1 / (1/w(x)_r + R_r^b / w(Tx)_r) (gvcm_offset.h gives w(Tx)_r and
// R_r = p_r(Tx)|T'|/p_r(x)); pixel j sampling T x with r and shifting it back has
// w_j,r = 1 / (1/w(Tx)_r + R_r^-b / w(x)_r). Their sum over r is 1 exactly when every R_r
// carries the same |T'| (the shift is one map for all strategies) and the VCM weights of
// base and offset each partition over the strategies; a strategy with a wrong R breaks it.
// The subpaths of every split are rebuilt from x's vertices (bidir_reference.h). Paths
// through Dirac vertices are skipped (their subpath walks' lobe records are not rebuilt;
// the stat tests cover them), as are pairs where some strategy's shift fails (T_0).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "integrators/gvcm/gvcm_offset.h"
#include "pathspace/bidir_connect.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/bidir_reference.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::test;
using pathspace::VcmPrefix;

namespace {

struct Outcome {
  double worst = 0;  // max |sum - 1|
  int64_t paths = 0, merges = 0, light_tracing = 0, skipped_dirac = 0, skipped_failed = 0;
};

// Deliberate defects: the merging shift's R without its area factor; a merge's R without
// the ratio of the offset's and the base's adaptive kernels.
enum class Defect { none, case2_area, kernel_ratio };

Outcome check(const scene::Scene& s, const pathspace::VcmMisConfig& mis, Defect defect, int samples) {
  Outcome o;
  const double beta = mis.heuristic == pathspace::MisHeuristic::power ? 2.0 : 1.0;
  const Vec2 offset(1, 0);
  const gradients::BidirShiftOptions opt;
  std::vector<BidirVertex> ls, cs;
  std::vector<VcmPrefix> lp, cp, off_cp, off_lp;
  gradients::CameraSubpathShift sh;
  gradients::LightTracingShift lt;
  gradients::MergeShift ms;
  integrators::GvcmCounters counters;
  const float norm = 1.0f;  // values are not compared here
  for_each_connection(s, 5, samples, 23, pathspace::MisConfig{.unweighted = true},
                      [&](int, const std::vector<BidirVertex>&, const std::vector<BidirVertex>&, int, int,
                          const pathspace::Connection&, const std::vector<BidirVertex>& x) {
    const int n = int(x.size());
    if (n < 3) return;  // one segment: never shifted
    const Reference ref = reference(s, x, beta == 2.0);
    for (const auto& v : ref.x)
      if (is_dirac(v)) {
        ++o.skipped_dirac;
        return;
      }
    const auto raster = s.camera().raster_of(x[size_t(n - 2)].sp.p);
    if (!raster || raster->x() + 1.0f >= float(s.camera().width())) return;
    double sum = 0;
    int merges = 0, lt_terms = 0;
    auto add = [&](const integrators::GvcmStrategy& st, double w_base) -> bool {
      if (!(w_base > 0)) return true;
      off_cp.resize(sh.path.size());
      pathspace::vcm_prefixes(sh.path.data(), int(sh.path.size()), true, mis, off_cp.data());
      const integrators::GvcmOffsetContext ctx{s, mis, norm, opt, cs, cp, sh, off_cp};
      integrators::GvcmOffset off;
      const int64_t case2 = counters.merge_case2_shifted;
      if (!integrators::gvcm_offset(ctx, st, offset, lt, ms, off_lp, off, counters) || !(off.w > 0) || !(off.R > 0))
        return false;
      if (defect == Defect::case2_area && counters.merge_case2_shifted > case2) off.R /= ms.area_ratio;
      if (defect == Defect::kernel_ratio && st.merge)
        off.R /= off_cp[size_t(st.t - 2)].m / cp[size_t(st.t - 2)].m;
      const double rb = std::pow(off.R, beta);
      sum += 1.0 / (1.0 / w_base + rb / off.w) + 1.0 / (1.0 / off.w + 1.0 / (rb * w_base));
      return true;
    };
    // Connections: every valid split s' (t' = n - s').
    for (int sp = 0; sp < n; ++sp) {
      if (!ref.valid[size_t(sp)]) continue;
      split(ref, sp, ls, cs);
      lp.resize(ls.size());
      cp.resize(cs.size());
      pathspace::vcm_prefixes(ls.data(), int(ls.size()), false, mis, lp.data());
      pathspace::vcm_prefixes(cs.data(), int(cs.size()), true, mis, cp.data());
      const int t = n - sp;
      const VcmPrefix* cpp = t == 1 ? &integrators::kGvcmPinholePrefix : cp.data();
      const double w = pathspace::vcm_connection_weight(s, ls.data(), lp.data(), sp, cs.data(), cpp, t, mis);
      if (t >= 2) gradients::shift_camera_subpath(s, cs, *raster, offset, opt, sh);
      else sh.path.clear();
      integrators::GvcmStrategy st;
      st.s = sp;
      st.t = t;
      st.raster = *raster;
      st.light = ls.data();
      st.lp = lp.data();
      lt_terms += t == 1;
      if (!add(st, w)) {
        ++o.skipped_failed;
        return;
      }
    }
    // Merges at every interior vertex x_j (light subpath x_0 .. x_j, camera x_{n-1} .. x_j).
    for (int j = 1; mis.eta > 0 && j + 1 < n; ++j) {
      std::vector<BidirVertex> unused;
      split(ref, j + 1, ls, unused);
      split(ref, j, unused, cs);
      lp.resize(ls.size());
      cp.resize(cs.size());
      pathspace::vcm_prefixes(ls.data(), int(ls.size()), false, mis, lp.data());
      pathspace::vcm_prefixes(cs.data(), int(cs.size()), true, mis, cp.data());
      const int t = n - j;
      integrators::GvcmStrategy st;
      st.merge = true;
      st.t = t;
      st.light = ls.data();
      st.j = j;
      st.photon = pathspace::vcm_photon_mis(ls.data(), lp.data(), j);
      st.photon_beta = Rgb::Ones();
      const double w = pathspace::vcm_merge_weight(st.photon, cs.data(), cp.data(), t, mis);
      gradients::shift_camera_subpath(s, cs, *raster, offset, opt, sh);
      ++merges;
      if (!add(st, w)) {
        ++o.skipped_failed;
        return;
      }
    }
    ++o.paths;
    o.merges += merges;
    o.light_tracing += lt_terms;
    o.worst = std::max(o.worst, std::abs(sum - 1.0));
  });
  return o;
}

}  // namespace

namespace {

// Both heuristics on `box`: the weights sum to 1 and `defect` breaks that (under the
// balance heuristic only when `defect_power` is false).
void check_sums(const scene::Scene& box, bool adaptive, Defect defect, bool defect_power, const char* label) {
  for (const auto heuristic : {pathspace::MisHeuristic::power, pathspace::MisHeuristic::balance}) {
    pathspace::VcmMisConfig mis;
    mis.heuristic = heuristic;
    mis.adaptive_kernel = adaptive;
    const float r = 0.01f * box.scene_radius();
    mis.eta = kPi * r * r * 256.0f;
    const Outcome o = check(box, mis, Defect::none, 400);
    const Outcome bad = check(box, mis, defect, 400);
    std::printf("gvcm mis%s [%s]: %lld path pairs (%lld merges, %lld light-tracing strategies), skipped %lld (Dirac) "
                "%lld (a shift failed); max |sum - 1| %.3g (fault: %s: %.3g)\n",
                adaptive ? ", adaptive kernel" : "", heuristic == pathspace::MisHeuristic::power ? "power" : "balance",
                (long long)o.paths, (long long)o.merges, (long long)o.light_tracing, (long long)o.skipped_dirac,
                (long long)o.skipped_failed, o.worst, label, bad.worst);
    REQUIRE(o.paths > 300);
    CHECK(o.merges > 300);
    CHECK(o.light_tracing > 100);
    // Float densities and Jacobians (u = 6e-8), a few dozen roundings per ratio: 1e-5.
    CHECK(o.worst < 1e-5);
    if (defect_power || heuristic == pathspace::MisHeuristic::balance) CHECK(bad.worst > 1e-5);
  }
}

scene::BsdfPtr conductor(float alpha) {
  return scene::make_two_sided(scene::make_conductor(alpha, alpha, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
}

}  // namespace

TEST_CASE("G-VCM: gradient MIS weights over active and passive strategies sum to 1 on sampled path pairs", "[unit]") {
  check_sums(*lit_box(conductor(0.3f), nullptr, 16), false, Defect::case2_area, true,
             "case-2 R without its area factor");
}

TEST_CASE("G-VCM: with the adaptive kernel the gradient MIS weights still sum to 1", "[unit]") {
  // Diffuse walls (r^2 x 0.25^10 past them) and two rough conductors (x 0.25^3 and
  // x 0.25^1): where the shift moves a camera vertex onto another material the offset's
  // kernel differs from the base's, and a merge's R must carry the ratio. Under the
  // power heuristic the merges whose two kernels differ weigh ~c^2 <= 1e-6 of their
  // paths: the defect stays at round-off there (measured 3e-7), so it is asserted with
  // the balance heuristic.
  check_sums(*lit_box(conductor(0.3f), conductor(0.1f), 16), true, Defect::kernel_ratio, false,
             "R without the kernel ratio");
}
