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
#include "scene/bsdfs.h"
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
      const bool ok = gradients::shift_merge(*s, light.data(), j, sh, {}, m);
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
      if (!gradients::shift_merge(*s, light.data(), j, sh, {}, m) || !m.walked) continue;
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
