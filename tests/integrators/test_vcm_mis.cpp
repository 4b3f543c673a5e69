// VCM's recursive MIS (pathspace/vcm_mis.h) against an explicit reference, on paths
// sampled by the real subpath walks and connections of the scenes of test_bdpt_mis (lit
// box with a rough conductor and a smooth glass sphere; furnace sphere with a point light;
// environment + directional light). For every connected path x of strategy (s, t):
//  (1) without merging (mode bpt) the O(1) weight on the walk's subpaths equals Veach's
//      explicit weight p_s^b / sum p_s'^b (tests/integrators/bidir_reference.h);
//  (2) with merging, the explicit reference adds one strategy per interior non-Dirac
//      surface vertex x_j, p_VM,j = prod_{i<=j} p_light(x_i) prod_{i>=j} p_camera(x_i) eta
//      (Georgiev et al. 2012, Eq. 11): the walk's weight equals the reference weight, and
//      the library's weights of x as sampled by EVERY connection and merge (subpaths
//      rebuilt from x's vertices) sum to 1;
//  (3) with the adaptive kernel (Sun et al. 2017, Sec. 6) the merge at x_j has
//      eta_j = eta * prod c(x_m) over the vertices between x_j and the pinhole,
//      c = 0.25^(10 min(1, roughness)) (1 where the path took a Dirac lobe), and (2) holds;
//  (4) all of them reject deliberate defects of the recursion (VcmFault).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/vcm_mis.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/bidir_reference.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using namespace dp::pathspace;
using namespace dp::test;

namespace {

struct Outcome {
  double max_sum_error = 0, max_weight_error = 0;
  int64_t paths = 0, with_merge = 0, with_dirac = 0, excluded = 0;  // excluded: merges below the roughness threshold
};

// `min_roughness`: VcmMisConfig::min_merge_roughness (no merge on smoother BSDFs).
bool mergeable_ref(const Reference& r, int j, float min_roughness) {
  const BidirVertex& v = r.x[size_t(j)];
  return j >= 1 && j + 1 < int(r.x.size()) && v.bsdf && !is_dirac(v) && !(v.bsdf->roughness() < min_roughness);
}

// The adaptive kernel's r^2 factor at a vertex (written out here, independent of vcm_mis.cpp).
double shrink_ref(const BidirVertex& v) {
  if (!v.bsdf || is_dirac(v)) return 1.0;
  return std::pow(0.25, 10.0 * std::min(1.0, double(v.bsdf->roughness())));
}

// Reference weight of connection s (merge = -1) or of the merge at x_merge.
double reference_weight(const Reference& r, double eta, float min_roughness, bool adaptive, bool power, int s,
                        int merge) {
  const int n = int(r.x.size());
  auto h = [power](double v) { return power ? v * v : v; };
  auto prod = [&](int sp) {  // light densities for i < sp, camera densities for i >= sp
    double p = 1.0;
    for (int i = 0; i < n; ++i) p *= i < sp ? r.pl[size_t(i)] : r.pc[size_t(i)];
    return p;
  };
  double sum = 0, self = 0;
  for (int sp = 0; sp < n; ++sp) {
    if (!r.valid[size_t(sp)]) continue;
    sum += h(prod(sp));
    if (sp == s && merge < 0) self = h(prod(sp));
  }
  if (eta > 0)
    for (int j = 1; j + 1 < n; ++j) {
      if (!mergeable_ref(r, j, min_roughness)) continue;
      double eta_j = eta;
      for (int m = j + 1; adaptive && m + 1 < n; ++m) eta_j *= shrink_ref(r.x[size_t(m)]);
      const double p = h(prod(j) * r.pl[size_t(j)] * eta_j);
      sum += p;
      if (j == merge) self = p;
    }
  return self / sum;
}

void prefixes(const std::vector<BidirVertex>& path, bool camera_side, const VcmMisConfig& c, std::vector<VcmPrefix>& out) {
  out.resize(path.size());
  vcm_prefixes(path.data(), int(path.size()), camera_side, c, out.data());
}

Outcome check_scene(const scene::Scene& scene, const VcmMisConfig& config, int samples, uint64_t seed) {
  Outcome o;
  const bool power = config.heuristic == MisHeuristic::power;
  const int max_depth = 6;
  std::vector<BidirVertex> ls, cs, unused;
  std::vector<VcmPrefix> lp, cp, lps, cps;
  int prefixed = -1;  // sample whose subpaths lp / cp belong to
  for_each_connection(scene, max_depth, samples, seed, MisConfig{.unweighted = true},
                      [&](int k, const std::vector<BidirVertex>& light, const std::vector<BidirVertex>& cam, int s, int t,
                          const Connection&, const std::vector<BidirVertex>& x) {
    if (k != prefixed) {
      prefixes(cam, true, config, cp);
      prefixes(light, false, config, lp);
      prefixed = k;
    }
    const Reference ref = reference(scene, x, power);
    const int n = int(ref.x.size());
    ++o.paths;
    bool dirac = false, merge = false;
    for (int j = 0; j < n; ++j) {
      dirac = dirac || is_dirac(ref.x[size_t(j)]);
      merge = merge || (config.eta > 0 && mergeable_ref(ref, j, config.min_merge_roughness));
      o.excluded += config.eta > 0 && mergeable_ref(ref, j, 0.0f) && !mergeable_ref(ref, j, config.min_merge_roughness);
    }
    o.with_dirac += dirac;
    o.with_merge += merge;
    const double w = vcm_connection_weight(scene, light.data(), lp.data(), s, cam.data(), cp.data(), t, config);
    o.max_weight_error = std::max(o.max_weight_error, std::abs(w - reference_weight(ref, config.eta, config.min_merge_roughness, config.adaptive_kernel, power, s, -1)));
    double sum = 0;
    for (int sp = 0; sp < n; ++sp) {
      if (!ref.valid[size_t(sp)]) continue;
      split(ref, sp, ls, cs);
      prefixes(ls, false, config, lps);
      prefixes(cs, true, config, cps);
      sum += double(vcm_connection_weight(scene, ls.data(), lps.data(), sp, cs.data(), cps.data(), n - sp, config));
    }
    for (int j = 1; config.eta > 0 && j + 1 < n; ++j) {
      if (!mergeable_ref(ref, j, config.min_merge_roughness)) continue;
      split(ref, j + 1, ls, unused);
      split(ref, j, unused, cs);
      prefixes(ls, false, config, lps);
      prefixes(cs, true, config, cps);
      const double wm = vcm_merge_weight(ls.data(), lps.data(), j, cs.data(), cps.data(), n - j, config);
      o.max_weight_error = std::max(o.max_weight_error, std::abs(wm - reference_weight(ref, config.eta, config.min_merge_roughness, config.adaptive_kernel, power, -1, j)));
      sum += wm;
    }
    o.max_sum_error = std::max(o.max_sum_error, std::abs(sum - 1.0));
  });
  return o;
}

std::unique_ptr<scene::Scene> glossy_glass_box() {
  return lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                             scene::ConductorFresnel{},
                                                             scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                 scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
}

// eta = pi r^2 N for r = 1% of the scene radius and a 32x32 image: merges compete with
// connections (p eta ~ 0.3 for densities ~ 1 / R^2).
float eta_of(const scene::Scene& s) {
  const float r = 0.01f * s.scene_radius();
  return kPi * r * r * 1024.0f;
}

void report(const char* what, const Outcome& o) {
  std::printf("vcm mis [%s]: %lld paths (%lld mergeable, %lld through a Dirac vertex), max |sum w - 1| %.3g, "
              "max |w - w_ref| %.3g\n",
              what, (long long)o.paths, (long long)o.with_merge, (long long)o.with_dirac, o.max_sum_error,
              o.max_weight_error);
}

}  // namespace

TEST_CASE("vcm: recursive weights equal the explicit ones and sum to 1 over connections and merges", "[unit]") {
  const auto box = glossy_glass_box();
  const auto furnace = furnace_sphere(0.5f, 0.5f, 1.0f, 16);
  const auto sky = env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                    scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                              16, 2.0f);
  constexpr double kTol = 2e-4;  // float densities, double sums (as test_bdpt_mis)
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance})
    for (const bool merging : {false, true})
      for (const auto* s : {box.get(), furnace.get(), sky.get()}) {
        VcmMisConfig config;
        config.heuristic = heuristic;
        config.eta = merging ? eta_of(*s) : 0.0f;
        const Outcome o = check_scene(*s, config, s == sky.get() ? 1000 : 300, 11);
        report((std::string(heuristic == MisHeuristic::power ? "power" : "balance") + (merging ? ", vcm" : ", bpt")).c_str(), o);
        REQUIRE(o.paths > 500);
        if (merging) CHECK(o.with_merge > 200);
        if (s == box.get()) CHECK(o.with_dirac > 20);
        CHECK(o.max_sum_error < kTol);
        CHECK(o.max_weight_error < kTol);
      }
}

TEST_CASE("vcm: with a merging roughness threshold the weights still equal the explicit ones and sum to 1",
          "[unit]") {
  // The rough conductor sphere (alpha 0.2) below a threshold of 0.25: its vertices lose
  // their merge strategies in the recursion and in the explicit reference alike.
  const auto box = glossy_glass_box();
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance}) {
    VcmMisConfig config;
    config.heuristic = heuristic;
    config.eta = eta_of(*box);
    config.min_merge_roughness = 0.25f;
    const Outcome o = check_scene(*box, config, 300, 12);
    report(heuristic == MisHeuristic::power ? "power, vcm, roughness >= 0.25" : "balance, vcm, roughness >= 0.25", o);
    std::printf("vcm mis: %lld merges excluded by the threshold\n", (long long)o.excluded);
    REQUIRE(o.paths > 500);
    CHECK(o.excluded > 50);
    CHECK(o.max_sum_error < 2e-4);
    CHECK(o.max_weight_error < 2e-4);
  }
}

TEST_CASE("vcm: the MIS check rejects a merge without its light prefix and a Dirac vertex kept", "[unit]") {
  const auto box = glossy_glass_box();
  for (const auto fault : {VcmFault::merge_without_light_prefix, VcmFault::dirac_interior_kept}) {
    VcmMisConfig config;
    config.eta = eta_of(*box);
    config.fault = fault;
    const Outcome o = check_scene(*box, config, 300, 11);
    report(fault == VcmFault::merge_without_light_prefix ? "fault: merge without light prefix" : "fault: Dirac kept", o);
    CHECK(o.max_sum_error > 0.05);
  }
}

TEST_CASE("vcm: with the adaptive kernel the weights equal the explicit ones and sum to 1", "[unit]") {
  // Diffuse walls shrink r^2 by 0.25^10, the conductor (alpha 0.2) by 0.25^2, glass not at
  // all: eta_j differs by orders of magnitude between the merges of one path.
  const auto box = glossy_glass_box();
  const auto sky = env_glossy(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                    scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
                              16, 2.0f);
  for (const auto heuristic : {MisHeuristic::power, MisHeuristic::balance})
    for (const auto* s : {box.get(), sky.get()}) {
      VcmMisConfig config;
      config.heuristic = heuristic;
      config.eta = eta_of(*s);
      config.adaptive_kernel = true;
      const Outcome o = check_scene(*s, config, s == sky.get() ? 1000 : 300, 13);
      report(heuristic == MisHeuristic::power ? "power, vcm, adaptive kernel" : "balance, vcm, adaptive kernel", o);
      REQUIRE(o.paths > 500);
      CHECK(o.with_merge > 200);
      CHECK(o.max_sum_error < 2e-4);
      CHECK(o.max_weight_error < 2e-4);
      // The light side's merges without the camera side's shrink: no longer a partition.
      config.fault = VcmFault::shrink_light_side_lost;
      const Outcome bad = check_scene(*s, config, s == sky.get() ? 1000 : 300, 13);
      report("fault: light-side merges without the camera shrink", bad);
      CHECK(bad.max_sum_error > 2e-4);  // the check above rejects it
    }
}
