// PrimarySampleStream: building a path, then replaying its recorded primary samples,
// gives the identical path; a mutated coordinate gives a different one (so the
// comparison can fail). Also checks the path convention (camera first) and that the
// walk's f/p (emission_estimate, from the recorded sample weights, pdfs and roulette)
// matches the measurement contribution over the area-measure density built from their
// definitions (BSDF eval/pdf, geometry terms, Veach 1997 Eq. 8.7 and 8.10).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "pathspace/measure.h"
#include "pathspace/path_builder.h"
#include "pathspace/scatter.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
bool same_path(const pathspace::Path& a, const pathspace::Path& b) {
  if (a.size() != b.size() || !(a.raster == b.raster)) return false;
  for (int k = 0; k < a.size(); ++k) {
    if (a[k].kind != b[k].kind || !(a[k].p() == b[k].p()) || a[k].lobe != b[k].lobe || a[k].pdf != b[k].pdf ||
        !(a[k].f_cos == b[k].f_cos).all())
      return false;
    const auto &la = a.nee[size_t(k)], &lb = b.nee[size_t(k)];
    if (la.valid != lb.valid || !(la.p == lb.p) || la.pdf != lb.pdf || la.visible != lb.visible) return false;
  }
  return true;
}

// f(x) / p(x) of the BSDF path x_0..x_k (x_k emitting toward x_{k-1}) from the definitions:
//   f = Le(x_k -> x_{k-1}) prod_{m=1}^{k-1} f_s(x_m) G(x_m, x_{m+1}),
//   p = prod_{m=1}^{k-1} pdf_sigma(x_m) |cos θ_{m+1}| / d_m^2 * rr_m,
// with f_s and pdf_sigma re-evaluated by the BSDF (not the values the walk recorded) and
// the camera segment's W_e G / p = 1 (box filter, measure.h). Only for paths whose
// scattering vertices x_1..x_{k-1} are all non-Dirac (eval has no Dirac lobes).
Rgbd fp_from_definitions(const pathspace::Path& path, int k) {
  Rgbd f = path[k].emission.cast<double>();
  double p = 1.0;
  for (int m = 1; m < k; ++m) {
    const pathspace::Vertex& v = path[m];
    const auto ctx = pathspace::radiance_context(v.hit);
    f *= v.hit.bsdf->eval(ctx, v.wi, v.wo).cast<double>() * pathspace::geometry_term(v, path[m + 1]);
    p *= double(v.hit.bsdf->pdf(ctx, v.wi, v.wo)) * pathspace::solid_angle_to_area(v, path[m + 1]) * double(v.rr);
  }
  return f / p;
}

// The same for the NEE path (x_0..x_k, y = nee[k]) on an area light: the last factor is
// f_s(x_k) G(x_k, y) Le(y) over the light pdf converted to area, pdf_sigma |cos θ_y| / d^2.
Rgbd nee_fp_from_definitions(const pathspace::Path& path, int k) {
  const pathspace::LightSample& ls = path.nee[size_t(k)];
  pathspace::Vertex y;
  y.hit.p = ls.p;
  y.hit.ng = ls.n;
  const pathspace::Vertex& v = path[k];
  const Rgbd f_last = v.hit.bsdf->eval(pathspace::radiance_context(v.hit), v.wi, ls.wo).cast<double>() *
                      pathspace::geometry_term(v, y) * ls.radiance.cast<double>();
  const double p_last = ls.pdf * pathspace::solid_angle_to_area(v, y);
  pathspace::Path prefix = path;  // x_0..x_k with x_k "emitting" 1: the prefix's f / p
  prefix[k].emission = Rgb::Ones();
  return fp_from_definitions(prefix, k) * f_last / p_last;
}

// Relative tolerance of the walk's f/p against the definitions for a path whose
// scattering vertices are x_1..x_n (n = k - 1 for an emitting path, k for NEE at x_k):
//  * positions: the definition's cosine at x_m (m < n, or m <= n - 1 for NEE: the NEE
//    segment is built from positions on both sides) uses the direction between the float
//    hit points x_m, x_{m+1}, the walk the sampled direction. Each hit point o + t d is off
//    by up to 4 ulps of its largest coordinate (2 roundings per coordinate, times sqrt 3),
//    so the directions differ by an angle up to 4 2^-24 (|x_m| + |x_{m+1}|) / d_m, which
//    changes cos theta_m relatively by that times |tan theta_m| <= 1 / |cos theta_m|
//    (observed: 1.6e-4 on a 0.5 mm segment into a corner of the box);
//  * BSDF factors: sample() and eval()/pdf() compute each vertex's factor by different
//    float formulas, ~16 operations at 2^-24 plus a direction error of ~8 ulps (frame
//    changes, normalizations) amplified by the lobe's |d ln D / d theta_h| <= 2 (1 +
//    alpha^2) / alpha for GGX (Walter et al. 2007, Eq. 33), alpha = 0.1 the sharpest
//    non-Dirac lobe of the scene, charged to every vertex: (16 + 8 x 20.2) 2^-24 = 1.1e-5.
double fp_tolerance(const pathspace::Path& path, int n, int continued) {
  const double ulp = std::ldexp(1.0, -24), alpha = 0.1;
  double tol = n * (16 + 8 * 2 * (1 + alpha * alpha) / alpha) * ulp;
  for (int m = 1; m <= continued; ++m) {
    const pathspace::Vertex& v = path[m];
    const pathspace::Vertex& next = path[m + 1];
    const double d = (next.p() - v.p()).cast<double>().norm();
    const double size = double(v.p().cwiseAbs().maxCoeff()) + double(next.p().cwiseAbs().maxCoeff());
    tol += 4 * ulp * size / (d * std::abs(double(v.wo.z())));
  }
  return tol;
}
}  // namespace

TEST_CASE("pathspace: replaying recorded primary samples rebuilds the identical path", "[unit]") {
  const auto s = test::lit_box(scene::make_two_sided(scene::make_conductor(0.1f, 0.1f, scene::MicrofacetType::ggx,
                                                                          scene::ConductorFresnel{})),
                               scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
  pathspace::WalkOptions opt;
  opt.max_depth = 12;
  opt.rr_depth = 3;
  const pathspace::PathBuilder builder(*s, opt);
  core::Rng rng(5, 1);
  int compared = 0, long_paths = 0, mutated_differs = 0, emission_checked = 0, nee_checked = 0;
  double worst_rel = 0;  // largest relative difference over its tolerance
  // 2000 paths: BSDF-sampled hits on the small ceiling light are ~5 % of them.
  for (int i = 0; i < 2000; ++i) {
    pathspace::PrimarySampleStream pss(rng);
    pathspace::Path a, b, c;
    builder.build(i % 16, (i / 16) % 16, pss, a);
    REQUIRE(a[0].kind == pathspace::VertexKind::camera);  // camera end first
    const size_t used = pss.used();
    pss.rewind();
    builder.build(i % 16, (i / 16) % 16, pss, b);
    REQUIRE(pss.used() == used);
    REQUIRE(same_path(a, b));
    ++compared;
    long_paths += a.size() > 3;
    // The walk's f/p of every emitting BSDF path and NEE path against the definitions.
    // Detects: a throughput without the roulette probability, a sample weight that is not
    // eval |cos| / pdf, a geometry term missing a cosine, an emission estimate dropping
    // the last vertex's factor (each seen failing, by 14 %..27x). Not detectable here: a wrongly recorded roulette probability
    // (the definition's p reads the same v.rr). Tolerance per path: fp_tolerance (float
    // positions and BSDF round-off), typically 1e-5..1e-4.
    for (int k = 2; k < a.size(); ++k) {
      bool smooth = a[k].is_surface() && !is_black(a[k].emission);
      for (int m = 1; m < k && smooth; ++m) smooth = a[m].continued() && !a[m].delta_lobe();
      if (!smooth) continue;
      const Rgbd walk = pathspace::emission_estimate(a, k).cast<double>();
      const Rgbd def = fp_from_definitions(a, k);
      const double tol = fp_tolerance(a, k - 1, k - 1);
      INFO("path " << i << " depth " << k << ": walk f/p " << walk.transpose() << ", definition " << def.transpose()
                   << ", relative tolerance " << tol);
      REQUIRE(((walk - def).abs() <= tol * def.abs().max(1e-6)).all());
      worst_rel = std::max(worst_rel, ((walk - def).abs() / def.abs().max(1e-6)).maxCoeff() / tol);
      ++emission_checked;
    }
    for (int k = 1; k < a.size(); ++k) {
      const pathspace::LightSample& ls = a.nee[size_t(k)];
      bool smooth = ls.valid && ls.visible && !ls.delta && !ls.infinite && ls.pdf > 0 && !is_black(ls.f_cos);
      for (int m = 1; m < k && smooth; ++m) smooth = a[m].continued() && !a[m].delta_lobe();
      if (!smooth) continue;
      const Rgbd walk = pathspace::nee_estimate(a, k).cast<double>();
      const Rgbd def = nee_fp_from_definitions(a, k);
      const double tol = fp_tolerance(a, k, k - 1);
      INFO("path " << i << " NEE at " << k << ": walk f/p " << walk.transpose() << ", definition " << def.transpose()
                   << ", relative tolerance " << tol);
      REQUIRE(((walk - def).abs() <= tol * def.abs().max(1e-6)).all());
      worst_rel = std::max(worst_rel, ((walk - def).abs() / def.abs().max(1e-6)).maxCoeff() / tol);
      ++nee_checked;
    }
    // Mutating the first BSDF coordinate of x_1 changes the path (the test can fail).
    if (a.size() > 2 && a[1].continued() && !a[1].delta_lobe() && pss.samples().size() > 6) {
      pss.mutable_samples()[6] = std::fmod(pss.samples()[6] + 0.37f, 1.0f);
      pss.rewind();
      builder.build(i % 16, (i / 16) % 16, pss, c);
      mutated_differs += !same_path(a, c);
    }
  }
  INFO("compared " << compared << ", long " << long_paths << ", mutated & different " << mutated_differs
                    << ", f/p checked: emission " << emission_checked << ", NEE " << nee_checked
                    << " (worst relative difference / tolerance " << worst_rel << ")");
  REQUIRE(long_paths > 20);
  REQUIRE(emission_checked >= 50);
  REQUIRE(nee_checked >= 500);
  REQUIRE(mutated_differs > 20);
}

TEST_CASE("pathspace: geometry term and area pdf follow their definitions", "[unit]") {
  pathspace::Vertex a, b;
  a.hit.p = Vec3(0, 0, 0);
  a.hit.ng = Vec3(0, 0, 1);
  b.hit.p = Vec3(0, 0, 2);
  b.hit.ng = Vec3(0, 0, -1);
  REQUIRE(pathspace::geometry_term(a, b) == Approx(0.25));
  b.hit.ng = Vec3(0, 1, 0);
  REQUIRE(pathspace::geometry_term(a, b) == Approx(0.0).margin(1e-12));
  pathspace::Path p;
  p.append(a).pdf = 2.0;
  b.hit.ng = Vec3(0, 0, -1);
  p.append(b);
  REQUIRE(pathspace::pdf_area(p, 0) == Approx(2.0 * 1.0 / 4.0));
}
