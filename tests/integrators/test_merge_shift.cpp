// G-VCM's vertex-merging shift at z_b (gradients/merge_shift.h; Sun et al. 2017, Sec. 4,
// case 2). (1) Connectable photon predecessor: the offset value equals the BDPT
// connection of the photon's light prefix with the offset camera prefix
// (pathspace::connect, an independent code path) over the photon's arrival density,
// Eq. 18; a variant without the area conversion at the new end is rejected. (2) Specular
// predecessor: the area factor through the walked chain (Eq. 19-20 for ideal specular
// chains) equals central differences of double-precision chain re-traces.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "gradients/merge_shift.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/chain_fd.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using pathspace::BidirVertex;

namespace {
scene::BsdfPtr mirror() { return scene::make_mirror(scene::constant_texture(Rgb::Constant(0.9f))); }
scene::BsdfPtr glass() { return scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx); }
scene::BsdfPtr glossy() {
  return scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                                                     scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
}
bool planar(const scene::Scene& s, const BidirVertex& v) {
  return v.kind == pathspace::BidirKind::light ||
         (v.shape >= 0 && s.shapes()[size_t(v.shape)]->kind() == scene::ShapeKind::mesh);
}
}  // namespace

TEST_CASE("G-VCM merging shift, connectable photon predecessor: the offset connection over the photon's density",
          "[unit]") {
  const auto s = test::lit_box(glossy(), nullptr, 32);
  core::Rng rng(21, 5);
  const pathspace::SubpathParams params{6, 5};
  const pathspace::MisConfig unweighted{.unweighted = true};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift sh;
  gradients::MergeShift m;
  int compared = 0, disagree = 0;
  double worst = 0;
  std::vector<double> broken;  // without the area conversion at z_b^off
  for (int i = 0; i < 3000 && compared < 2000; ++i) {
    const Vec2 raster(1.0f + 30.0f * rng.uniform(), 1.0f + 30.0f * rng.uniform());
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    gradients::shift_camera_subpath(*s, cam, raster, Vec2(1, 0), {}, sh);
    pathspace::light_subpath(*s, params, rng, light);
    const int b = sh.b;
    if (b < 1 || sh.alive <= b) continue;
    for (int j = 1; j < int(light.size()); ++j) {
      if (light[size_t(j - 1)].kind != pathspace::BidirKind::light && light[size_t(j - 1)].delta) continue;
      const bool ok = gradients::shift_merge(*s, light.data(), j, cam, sh, {}, m);
      pathspace::Connection c;
      const bool ref = pathspace::connect(*s, light.data(), j, sh.path.data(), b + 1, unweighted, c) &&
                       !is_black(c.value);
      if (ok != ref) {
        ++disagree;
        continue;
      }
      if (!ok) continue;
      // The photon's arrival density as the light walk drew it: the sampled direction's
      // density (as the shift's base density) converted to area at the photon.
      const BidirVertex &y = light[size_t(j - 1)], &ph = light[size_t(j)];
      const Vec3d d = (ph.sp.p - y.sp.p).cast<double>();
      const double p_photon = double(y.pdf_out) * double(y.rr_out) *
                              std::abs(ph.sp.ng.cast<double>().dot(d.normalized())) / d.squaredNorm();
      const double expect = double(c.value.maxCoeff()) / p_photon;
      worst = std::max(worst, std::abs(double(m.value.maxCoeff()) / expect - 1.0));
      broken.push_back(std::abs(double(m.value.maxCoeff()) / m.area_ratio / expect - 1.0));
      ++compared;
    }
  }
  std::sort(broken.begin(), broken.end());
  const double broken_median = broken.empty() ? 0.0 : broken[broken.size() / 2];
  std::printf("gvcm merging shift (connectable predecessor): %d compared, %d disagree on existence, worst relative "
              "error %.2e; without the area conversion: median %.2e\n",
              compared, disagree, worst, broken_median);
  REQUIRE(compared >= 500);
  CHECK(disagree == 0);
  CHECK(worst <= 1e-4);
  CHECK(broken_median > 1e-2);
}

TEST_CASE("G-VCM merging shift, specular photon predecessor: the walked chain's area factor equals finite differences",
          "[unit]") {
  // |d w_d / dA(z_b^off)| / |d w_d / dA(photon)| through the chain pinned at y_d:
  // (dA(photon)/d w_d) / (dA(z_b^off)/d w'_d), both by re-tracing from y_d in double.
  const auto s = test::lit_box(mirror(), glass(), 64);
  core::Rng rng(23, 9);
  const pathspace::SubpathParams params{6, 5};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift sh;
  gradients::MergeShift m;
  int checked = 0, walked = 0;
  double worst = 0;
  for (int i = 0; i < 40000 && checked < 40; ++i) {
    const Vec2 raster(1.0f + 62.0f * rng.uniform(), 1.0f + 62.0f * rng.uniform());
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    gradients::shift_camera_subpath(*s, cam, raster, Vec2(1, 0), {}, sh);
    if (sh.b < 1 || sh.alive <= sh.b || !planar(*s, sh.path[size_t(sh.b)])) continue;
    pathspace::light_subpath(*s, params, rng, light);
    for (int j = 2; j < int(light.size()) && checked < 40; ++j) {
      if (!gradients::chain_interior(light[size_t(j - 1)]) || !planar(*s, light[size_t(j)])) continue;
      if (!gradients::shift_merge(*s, light.data(), j, cam, sh, {}, m) || !m.walked) continue;
      ++walked;
      const auto cx = test::fd_chain(*s, test::camera_order(light, m.e, j));
      const auto cy = test::fd_chain(*s, test::camera_order(m.light, m.e, j));
      if (!cx || !cy) continue;
      manifold::Chain rx = *cx, ry = *cy;  // pinned at y_d = light[e]
      std::reverse(rx.v.begin(), rx.v.end());
      std::reverse(ry.v.begin(), ry.v.end());
      const double ax = test::area_per_solid_angle(*s, rx), ay = test::area_per_solid_angle(*s, ry);
      if (!(ax > 0.0) || !(ay > 0.0)) continue;
      worst = std::max(worst, std::abs((ax / ay) / m.area_ratio - 1.0));
      ++checked;
    }
  }
  std::printf("gvcm merging shift (specular predecessor): %d walked merges, %d checked, worst relative error vs FD "
              "%.2e\n",
              walked, checked, worst);
  REQUIRE(checked >= 20);
  CHECK(worst <= 1e-4);
}

TEST_CASE("G-VCM merging shift is bijective on physical paths: shifted back, the path returns, area factors multiply "
          "to 1",
          "[unit]") {
  // The map acts on the physical path y_0 .. y_s [chain] z_b .. z_0 (the photon at the
  // kernel's centre, r -> 0): build it by rejoining the photon's light prefix at z_b,
  // shift it to pixel j, shift the result back to pixel i.
  const auto s = test::lit_box(mirror(), glass(), 16);
  core::Rng rng(29, 3);
  const pathspace::SubpathParams params{6, 5};
  std::vector<BidirVertex> cam, light, offset_cam;
  gradients::CameraSubpathShift sh, rsh;
  gradients::LightRejoin physical;
  gradients::MergeShift m, back;
  int tried = 0, returned = 0, walked = 0, grazing = 0, unexplained = 0;
  double worst_p = 0, worst_j = 0, worst_ratio = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec2 raster(1.0f + 14.0f * rng.uniform(), 1.0f + 14.0f * rng.uniform());
    const Vec2 off = i % 2 ? Vec2(1, 0) : Vec2(0, -1);
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    gradients::shift_camera_subpath(*s, cam, raster, off, {}, sh);
    const int b = sh.b;
    if (b < 1 || sh.alive <= b || int(cam.size()) <= b) continue;
    pathspace::light_subpath(*s, params, rng, light);
    for (int j = 1; j < int(light.size()); ++j) {
      if (!gradients::rejoin_light_subpath(*s, light.data(), j, cam[size_t(b)], {}, physical)) continue;
      if (!gradients::shift_merge(*s, physical.light.data(), j, cam, sh, {}, m)) continue;
      ++tried;
      walked += m.walked;
      offset_cam.assign(sh.path.begin(), sh.path.begin() + sh.alive);
      gradients::shift_camera_subpath(*s, offset_cam, raster + off, -off, {}, rsh);
      if (rsh.b != b || !gradients::shift_merge(*s, m.light.data(), j, offset_cam, rsh, {}, back)) {
        // Allowed only where float round-off decides a side: a grazing direction at z_b or
        // at the light vertex it connects to (|cos| < 1e-3 against the geometric normal).
        const BidirVertex &z = cam[size_t(b)], &y = physical.light[size_t(j - 1)];
        const Vec3 w = (y.sp.p - z.sp.p).normalized();
        const float c = std::min({std::abs(z.sp.ng.dot(w)), std::abs(z.sp.ng.dot(z.wi)),
                                  y.kind == pathspace::BidirKind::light ? 1.0f : std::abs(y.sp.ng.dot(w))});
        ++(c < 1e-3f ? grazing : unexplained);
        continue;
      }
      ++returned;
      for (int k = m.e + 1; k <= j; ++k)
        worst_p = std::max(worst_p, double((back.light[size_t(k)].sp.p - physical.light[size_t(k)].sp.p).norm()));
      // The area factors multiply to 1 within the first-order round-off bound of the
      // vertices they read (z_b .. y_e, camera order), tests/support/jj_bound.h.
      const auto xs = test::camera_order(physical.light, m.e, j), bs = test::camera_order(back.light, m.e, j);
      const double jj = std::abs(m.area_ratio * back.area_ratio - 1.0);
      worst_j = std::max(worst_j, jj);
      worst_ratio = std::max(worst_ratio, jj / test::bidir_jj_tolerance(xs, bs, 0, int(xs.size()) - 1));
    }
  }
  std::printf("gvcm merging shift bijectivity: %d shifted (%d through a walked chain), %d back, %d not back at a "
              "grazing direction, %d otherwise; worst position error %.2e, worst |a a' - 1| %.2e (%.2f of its "
              "per-sample bound)\n",
              tried, walked, returned, grazing, unexplained, worst_p, worst_j, worst_ratio);
  REQUIRE(tried > 200);
  REQUIRE(walked > 20);
  CHECK(unexplained == 0);
  CHECK(returned + grazing == tried);
  CHECK(worst_p < 1e-4);
  CHECK(worst_ratio <= 1.0);
}
