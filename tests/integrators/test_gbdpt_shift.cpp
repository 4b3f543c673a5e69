// The G-BDPT shift (gradients/bidir_shift.h): its Jacobians against central finite
// differences of the traced maps (Richardson-extrapolated, rel <= 1e-4), its bijectivity
// (shifting the offset back recovers the base, the two Jacobians multiply to 1), and the
// zero-gradient furnace (every offset's value equals its base's within the float
// round-off bound, tests/support/furnace_bound.h; a Jacobian defect is rejected).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/rng.h"
#include "gradients/bidir_shift.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "scene/bsdfs.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/test_scenes.h"

using namespace dp;
using pathspace::BidirVertex;

namespace {
constexpr int kRes = 16;

std::unique_ptr<scene::Scene> glossy_glass_box() {
  return test::lit_box(scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                                   scene::ConductorFresnel{},
                                                                   scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f)))),
                       scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), kRes);
}

// Central difference of f (a 3D point or direction map of 2 parameters) with Richardson
// extrapolation (h, h/2): error O(h^4) instead of O(h^2).
template <class F>
Vec3d derivative(F&& f, int axis, double h) {
  auto central = [&](double s) {
    const double a = axis == 0 ? s : 0.0, b = axis == 1 ? s : 0.0;
    return Vec3d((f(a, b) - f(-a, -b)) / (2.0 * s));
  };
  return Vec3d((4.0 * central(h / 2) - central(h)) / 3.0);
}

bool on_same_plane(const scene::SurfaceHit& a, const scene::SurfaceHit& b) {
  return a.shape == b.shape && (a.ng - b.ng).norm() < 1e-6f && std::abs(a.ng.dot(b.p - a.p)) < 1e-5f;
}
}  // namespace

TEST_CASE("G-BDPT light-tracing Jacobian |dy_1/dx_1| equals finite differences of the traced map", "[unit]") {
  const auto s = test::lit_box(nullptr, nullptr, 64);
  const auto& cam = s->camera();
  const Vec2 offset(1, 0);
  core::Rng rng(3, 1);
  pathspace::SubpathParams params{4, 5};
  std::vector<BidirVertex> light;
  gradients::LightTracingShift lt;
  int checked = 0;
  double worst = 0;
  for (int i = 0; i < 4000 && checked < 40; ++i) {
    pathspace::light_subpath(*s, params, rng, light);
    if (light.size() < 2 || !light[1].bsdf) continue;
    const auto raster = cam.raster_of(light[1].sp.p);
    if (!raster || raster->x() + 2 > float(cam.width()) || raster->y() < 1 || raster->y() + 1 > float(cam.height()))
      continue;
    if (!gradients::shift_light_tracing(*s, light.data(), 2, *raster, offset, {}, lt)) continue;
    const BidirVertex& x1 = light[1];
    // The map x_1 -> y_1 over x_1's plane: project, move one pixel, trace.
    scene::SurfaceHit y0;
    if (!s->intersect(cam.generate_ray(*raster + offset), y0)) continue;
    bool planar = true;
    const Vec3d e0 = x1.sp.shading.s.cast<double>(), e1 = x1.sp.shading.t.cast<double>();
    auto map = [&](double a, double b) -> Vec3d {
      const Vec3 p = (x1.sp.p.cast<double>() + a * e0 + b * e1).cast<float>();
      const auto r = cam.raster_of(p);
      scene::SurfaceHit h;
      if (!r || !s->intersect(cam.generate_ray(*r + offset), h) || !on_same_plane(h, y0)) {
        planar = false;
        return Vec3d::Zero();
      }
      return h.p.cast<double>();
    };
    const double h = 2e-2;
    const Vec3d du = derivative(map, 0, h), dv = derivative(map, 1, h);
    if (!planar) continue;  // the perturbation left x_1's or y_1's plane
    const double fd = du.cross(dv).norm();  // |e0 x e1| = 1
    const double rel = std::abs(fd / lt.jacobian - 1.0);
    worst = std::max(worst, rel);
    ++checked;
  }
  std::printf("gbdpt light-tracing Jacobian: %d paths, worst relative error vs FD %.2e\n", checked, worst);
  REQUIRE(checked >= 20);
  CHECK(worst <= 1e-4);
}

TEST_CASE("G-BDPT camera reconnection Jacobian equals finite differences of the traced direction map", "[unit]") {
  const auto s = test::lit_box(nullptr, nullptr, 64);
  core::Rng rng(5, 2);
  pathspace::SubpathParams params{4, 5};
  std::vector<BidirVertex> cam;
  gradients::CameraSubpathShift sh;
  int checked = 0;
  double worst = 0;
  for (int i = 0; i < 4000 && checked < 40; ++i) {
    const Vec2 raster(1.0f + 60.0f * rng.uniform(), 1.0f + 60.0f * rng.uniform());
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    if (cam.size() < 3 || cam[2].kind != pathspace::BidirKind::surface) continue;
    // Well-conditioned for float finite differences: a hit moves by ~d h = 2e-3 for h =
    // 1e-2 at d >= 0.2, against float position noise ~1e-7 (relative 5e-5 before
    // extrapolation); grazing targets amplify it by 1 / cos.
    const Vec3 seg = cam[2].sp.p - cam[1].sp.p;
    if (seg.norm() < 0.2f || std::abs(cam[2].sp.ng.dot(seg.normalized())) < 0.1f) continue;
    gradients::shift_camera_subpath(*s, cam, raster, Vec2(0, 1), {}, sh);
    if (!sh.rejoined || sh.b != 1) continue;
    const Vec3d x1 = cam[1].sp.p.cast<double>(), y1 = sh.path[1].sp.p.cast<double>();
    const Vec3d w = (cam[2].sp.p.cast<double>() - x1).normalized();
    const Frame f = Frame::from_normal(w.cast<float>());
    const Vec3d e0 = f.s.cast<double>(), e1 = f.t.cast<double>();
    // Rays leave x_1 itself, as the walk's (pathspace::next_hit).
    scene::SurfaceHit x1_hit, ref;
    if (!s->intersect(s->camera().generate_ray(raster), x1_hit) ||
        !pathspace::next_hit(*s, x1_hit, w.cast<float>(), ref))
      continue;
    bool planar = true;
    // Base direction (on the tangent plane of the unit sphere at w) -> offset direction.
    auto map = [&](double a, double b) -> Vec3d {
      const Vec3d d = (w + a * e0 + b * e1).normalized();
      scene::SurfaceHit h;
      if (!pathspace::next_hit(*s, x1_hit, d.cast<float>(), h) || !on_same_plane(h, ref)) {
        planar = false;
        return Vec3d::Zero();
      }
      return (h.p.cast<double>() - y1).normalized();
    };
    // The gnomonic parameterization w + a e0 + b e1 has solid-angle density 1 at (0, 0).
    const double h = 1e-2;
    const Vec3d du = derivative(map, 0, h), dv = derivative(map, 1, h);
    if (!planar) continue;
    const double fd = du.cross(dv).norm();
    worst = std::max(worst, std::abs(fd / sh.jacobian - 1.0));
    ++checked;
  }
  std::printf("gbdpt camera reconnection Jacobian: %d paths, worst relative error vs FD %.2e\n", checked, worst);
  REQUIRE(checked >= 20);
  CHECK(worst <= 1e-4);
}

TEST_CASE("G-BDPT shifts are bijective: the offset shifted back is the base, Jacobians multiply to 1", "[unit]") {
  const auto s = glossy_glass_box();
  core::Rng rng(9, 4);
  pathspace::SubpathParams params{7, 5};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift fwd, rev;
  gradients::LightTracingShift lf, lr;
  int tried = 0, rejoined = 0, through_dirac = 0, back = 0, lt_tried = 0, lt_back = 0;
  double worst_p = 0, worst_j = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 raster(1.0f + 14.0f * rng.uniform(), 1.0f + 14.0f * rng.uniform());
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    const Vec2 off = i % 2 ? Vec2(1, 0) : Vec2(0, -1);
    ++tried;
    gradients::shift_camera_subpath(*s, cam, raster, off, {}, fwd);
    if (fwd.rejoined) {
      ++rejoined;
      through_dirac += fwd.b > 1;
      std::vector<BidirVertex> offset_path(fwd.path.begin(), fwd.path.begin() + fwd.alive);
      gradients::shift_camera_subpath(*s, offset_path, raster + off, -off, {}, rev);
      if (rev.rejoined && rev.b == fwd.b) {
        ++back;
        for (int k = 0; k < std::min(rev.alive, int(cam.size())); ++k)
          worst_p = std::max(worst_p, double((rev.path[size_t(k)].sp.p - cam[size_t(k)].sp.p).norm()));
        worst_j = std::max(worst_j, std::abs(fwd.jacobian * rev.jacobian - 1.0));
      }
    }
    pathspace::light_subpath(*s, params, rng, light);
    for (int sl = 2; sl <= int(light.size()); ++sl) {
      const auto r = s->camera().raster_of(light[size_t(sl - 1)].sp.p);
      if (!r || r->x() < 1 || r->y() < 1 || r->x() + 1 > kRes - 1 || r->y() + 1 > kRes - 1) continue;
      pathspace::Connection c;  // a light-tracing contribution: x_1 seen by the camera
      if (!pathspace::connect(*s, light.data(), sl, cam.data(), 1, pathspace::MisConfig{}, c)) continue;
      if (!gradients::shift_light_tracing(*s, light.data(), sl, *r, off, {}, lf)) continue;
      ++lt_tried;
      if (!gradients::shift_light_tracing(*s, lf.light.data(), sl, *r + off, -off, {}, lr)) continue;
      ++lt_back;
      worst_p = std::max(worst_p, double((lr.light.back().sp.p - light[size_t(sl - 1)].sp.p).norm()));
      // J = p_cam(x_1) / p_cam(y_1) holds the cosines toward the pinhole: at grazing views
      // (|cos| < 0.1) float positions alone move it by more than the tolerance.
      const auto graze = [&](const BidirVertex& v) {
        return std::abs(v.sp.ng.dot((s->camera().position() - v.sp.p).normalized())) < 0.1f;
      };
      if (graze(light[size_t(sl - 1)]) || graze(lf.light.back())) continue;
      worst_j = std::max(worst_j, std::abs(lf.jacobian * lr.jacobian - 1.0));
    }
  }
  std::printf("gbdpt bijectivity: camera %d shifts, %d rejoined (%d after Dirac copies), %d shifted back; light "
              "tracing %d shifted, %d back; worst position error %.2e, worst |J J' - 1| %.2e\n",
              tried, rejoined, through_dirac, back, lt_tried, lt_back, worst_p, worst_j);
  REQUIRE(rejoined > tried / 4);
  REQUIRE(through_dirac > 10);
  CHECK(back == rejoined);
  CHECK(lt_back == lt_tried);
  CHECK(worst_p < 1e-4);
  CHECK(worst_j < 1e-4);
}

namespace {
// Worst |value(T x)/value(x) - 1| / eps(d_min) over every strategy of every sample in the
// furnace sphere, and the number of offsets that failed to exist.
struct FurnaceResult {
  double worst = 0;
  int64_t terms = 0, missing = 0;
};
FurnaceResult furnace_offsets(const scene::Scene& s, gradients::JacobianFault fault) {
  const gradients::BidirShiftOptions opt{fault};
  pathspace::MisConfig mis;
  core::Rng rng(1, 2);
  pathspace::SubpathParams params{7, 3};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift sh;
  gradients::LightTracingShift lt;
  FurnaceResult out;
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int py = 1; py + 1 < kRes; ++py)
    for (int px = 1; px + 1 < kRes; ++px) {
      const Vec2 raster(float(px) + rng.uniform(), float(py) + rng.uniform());
      pathspace::camera_subpath(s, raster, params, rng, cam);
      pathspace::light_subpath(s, params, rng, light);
      double d_min = std::numeric_limits<double>::infinity();
      auto scan = [&](const BidirVertex* v, int n) {
        for (int k = 1; k + 1 < n; ++k) d_min = std::min(d_min, double((v[k].sp.p - v[k + 1].sp.p).norm()));
      };
      scan(cam.data(), int(cam.size()));
      scan(light.data(), int(light.size()));
      for (int nb = 0; nb < 4; ++nb) {
        const Vec2 off(float(kDx[nb]), float(kDy[nb]));
        gradients::shift_camera_subpath(s, cam, raster, off, opt, sh);
        scan(sh.path.data(), sh.alive);
        for (int t = 1; t <= int(cam.size()); ++t)
          for (int sl = 0; sl <= int(light.size()); ++sl) {
            if (sl + t <= 2) continue;
            pathspace::Connection c, o;
            if (!pathspace::connect(s, light.data(), sl, cam.data(), t, mis, c)) continue;
            // Where the pair's segments meet: the connection of base and offset.
            double dm = d_min;
            if (sl > 0 && t > 1)
              dm = std::min(dm, double((light[size_t(sl - 1)].sp.p - cam[size_t(t - 1)].sp.p).norm()));
            Rgb value = Rgb::Zero();
            if (t >= 2) {
              const auto so = gradients::camera_strategy_offset(sh, cam, t);
              if (so.exists && pathspace::connect(s, light.data(), sl, sh.path.data(), t, mis, o, so.test_visibility))
                value = o.value;
              if (sl > 0 && t - 1 < sh.alive)
                dm = std::min(dm, double((light[size_t(sl - 1)].sp.p - sh.path[size_t(t - 1)].sp.p).norm()));
            } else {
              const auto r = s.camera().raster_of(light[size_t(sl - 1)].sp.p);
              if (!r) continue;
              const Vec2 q = *r + off;  // the integrator forms no pair with a pixel outside
              if (q.x() < 0 || q.y() < 0 || q.x() >= float(kRes) || q.y() >= float(kRes)) continue;
              if (!gradients::shift_light_tracing(s, light.data(), sl, *r, off, opt, lt)) {
                ++out.missing;
                continue;
              }
              value = lt.value;
              dm = std::min(dm, double((lt.light.back().sp.p - light[size_t(sl - 2)].sp.p).norm()));
            }
            ++out.terms;
            if (is_black(value)) {
              ++out.missing;
              continue;
            }
            const double rel = std::abs(double(value.maxCoeff()) / double(c.value.maxCoeff()) - 1.0);
            out.worst = std::max(out.worst, rel / test::furnace_roundoff_bound(dm));
          }
      }
    }
  return out;
}
}  // namespace

TEST_CASE("G-BDPT furnace: every offset equals its base within the round-off bound; J = 1 is rejected", "[unit]") {
  const auto s = test::furnace_sphere(0.5f, 0.5f, 0.0f, kRes);
  const FurnaceResult ok = furnace_offsets(*s, gradients::JacobianFault::none);
  const FurnaceResult bad = furnace_offsets(*s, gradients::JacobianFault::unit);
  std::printf("gbdpt furnace: %lld strategy offsets, %lld missing; worst |value ratio - 1| / eps: %.3f (fault J = 1: "
              "%.3g)\n",
              (long long)ok.terms, (long long)ok.missing, ok.worst, bad.worst);
  REQUIRE(ok.terms > 1000);
  CHECK(ok.missing == 0);  // a closed diffuse sphere: every shift succeeds
  CHECK(ok.worst <= 1.0);
  CHECK(bad.worst > 1.0);
}
