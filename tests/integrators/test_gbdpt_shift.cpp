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
#include "manifold/local_geometry.h"
#include "manifold/walk.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/emitters/emitter.h"
#include "scene/shapes/shape.h"
#include "tests/support/furnace_bound.h"
#include "tests/support/chain_fd.h"
#include "tests/support/jj_bound.h"
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

bool on_same_plane(const scene::SurfaceHit& a, const scene::SurfaceHit& b) {
  return a.shape == b.shape && (a.ng - b.ng).norm() < 1e-6f && std::abs(a.ng.dot(b.p - a.p)) < 1e-5f;
}

using test::bidir_jj_tolerance;
using test::derivative;
using test::camera_order;
using test::fd_chain;
using test::area_per_solid_angle;

scene::BsdfPtr mirror() { return scene::make_mirror(scene::constant_texture(Rgb::Constant(0.9f))); }
scene::BsdfPtr glass() { return scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx); }

template <class V>
std::vector<const BidirVertex*> pointers(const V& v, int n) {
  std::vector<const BidirVertex*> out;
  for (int k = 0; k < n; ++k) out.push_back(&v[size_t(k)]);
  return out;
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


TEST_CASE("G-BDPT walked-chain Jacobians equal finite differences of the traced chains", "[unit]") {
  // Camera side: |d w'_b / d w_b| = (dA_c/d w_b) / (dA_c/d w'_b) through the base's and the
  // offset's chains; light tracing: [d w'_c / dA(y_1)] / [d w_c / dA(x_1)] = (dA(x_1)/d w_c)
  // / (dA(y_1)/d w'_c). Chain ends on the box's planar walls or the light.
  const auto s = test::lit_box(mirror(), glass(), 64);
  core::Rng rng(13, 7);
  pathspace::SubpathParams params{6, 5};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift sh;
  gradients::LightTracingShift lt;
  auto planar = [&](const BidirVertex& v) {
    return v.kind == pathspace::BidirKind::light ||
           (v.shape >= 0 && s->shapes()[size_t(v.shape)]->kind() == scene::ShapeKind::mesh);
  };
  int cam_checked = 0, lt_checked = 0;
  double cam_worst = 0, lt_worst = 0;
  // A broken variant: the ratio of generalized geometry terms without the cosines at the
  // sampled vertex (G'/G alone); its median error must be far above the tolerance.
  std::vector<double> broken;
  auto cosine = [](const BidirVertex& a, const BidirVertex& b) {
    return std::abs(double(a.sp.ng.dot((b.sp.p - a.sp.p).normalized())));
  };
  for (int i = 0; i < 20000 && (cam_checked < 40 || lt_checked < 40); ++i) {
    const Vec2 raster(1.0f + 62.0f * rng.uniform(), 1.0f + 62.0f * rng.uniform());
    pathspace::camera_subpath(*s, raster, params, rng, cam);
    gradients::shift_camera_subpath(*s, cam, raster, Vec2(1, 0), {}, sh);
    if (cam_checked < 40 && sh.walked && sh.rejoined && planar(cam[size_t(sh.join)])) {
      std::vector<const BidirVertex*> xs, ys;
      for (int k = sh.b; k <= sh.join; ++k) {
        xs.push_back(&cam[size_t(k)]);
        ys.push_back(&sh.path[size_t(k)]);
      }
      const auto cx = fd_chain(*s, xs), cy = fd_chain(*s, ys);
      const double ax = cx ? area_per_solid_angle(*s, *cx) : 0.0, ay = cy ? area_per_solid_angle(*s, *cy) : 0.0;
      if (ax > 0.0 && ay > 0.0) {
        cam_worst = std::max(cam_worst, std::abs((ax / ay) / sh.jacobian - 1.0));
        const double no_cos = sh.jacobian * cosine(*ys[0], *ys[1]) / cosine(*xs[0], *xs[1]);
        broken.push_back(std::abs((ax / ay) / no_cos - 1.0));
        ++cam_checked;
      }
    }
    pathspace::light_subpath(*s, params, rng, light);
    for (int sl = 3; sl <= int(light.size()) && lt_checked < 40; ++sl) {
      const auto r = s->camera().raster_of(light[size_t(sl - 1)].sp.p);
      if (!r || r->x() < 1 || r->y() < 1 || r->x() + 2 > 64.0f || r->y() + 1 > 64.0f) continue;
      if (!planar(light[size_t(sl - 1)])) continue;
      if (!gradients::shift_light_tracing(*s, light.data(), sl, *r, Vec2(1, 0), {}, lt) || !lt.walked) continue;
      if (!planar(lt.light.back())) continue;
      const int e = int(lt.light.size()) - 2 - int(lt.chain.steps.size());
      const auto cx = fd_chain(*s, camera_order(light, e, sl - 1)), cy = fd_chain(*s, camera_order(lt.light, e, sl - 1));
      if (!cx || !cy) continue;
      manifold::Chain rx = *cx, ry = *cy;  // pinned at z = light[e]
      std::reverse(rx.v.begin(), rx.v.end());
      std::reverse(ry.v.begin(), ry.v.end());
      const double ax = area_per_solid_angle(*s, rx), ay = area_per_solid_angle(*s, ry);
      if (!(ax > 0.0) || !(ay > 0.0)) continue;
      lt_worst = std::max(lt_worst, std::abs((ax / ay) / lt.chain.start_density - 1.0));
      const BidirVertex& z = light[size_t(e)];
      if (z.kind != pathspace::BidirKind::light) {  // an area light's cosine stays in G
        const double no_cos = lt.chain.start_density * cosine(z, lt.light[size_t(e + 1)]) / cosine(z, light[size_t(e + 1)]);
        broken.push_back(std::abs((ax / ay) / no_cos - 1.0));
      }
      ++lt_checked;
    }
  }
  std::sort(broken.begin(), broken.end());
  const double broken_median = broken.empty() ? 0.0 : broken[broken.size() / 2];
  std::printf("gbdpt walked-chain Jacobians vs FD: camera %d chains, worst relative error %.2e; light tracing %d "
              "chains, worst %.2e; without the cosines at the sampled vertex: median %.2e\n",
              cam_checked, cam_worst, lt_checked, lt_worst, broken_median);
  REQUIRE(cam_checked >= 20);
  REQUIRE(lt_checked >= 20);
  CHECK(cam_worst <= 1e-4);
  CHECK(lt_worst <= 1e-4);
  CHECK(broken_median > 1e-3);
}

namespace {
struct RoundTrip {
  int tried = 0, rejoined = 0, through_dirac = 0, walked = 0, back = 0, lt_tried = 0, lt_walked = 0, lt_back = 0;
  int jj_over = 0;          // products beyond their per-sample bound (tests/support/jj_bound.h)
  double worst_p = 0, worst_j = 0, worst_ratio = 0;
  void jac(double jj, double bound) {
    worst_j = std::max(worst_j, jj);
    worst_ratio = std::max(worst_ratio, jj / bound);
    jj_over += !(jj <= bound);
  }
};

RoundTrip round_trip(const scene::Scene& s, int samples, uint64_t seed) {
  core::Rng rng(seed, 4);
  pathspace::SubpathParams params{7, 5};
  std::vector<BidirVertex> cam, light;
  gradients::CameraSubpathShift fwd, rev;
  gradients::LightTracingShift lf, lr;
  RoundTrip r;
  for (int i = 0; i < samples; ++i) {
    const Vec2 raster(1.0f + 14.0f * rng.uniform(), 1.0f + 14.0f * rng.uniform());
    pathspace::camera_subpath(s, raster, params, rng, cam);
    const Vec2 off = i % 2 ? Vec2(1, 0) : Vec2(0, -1);
    ++r.tried;
    gradients::shift_camera_subpath(s, cam, raster, off, {}, fwd);
    if (fwd.rejoined) {
      ++r.rejoined;
      r.through_dirac += fwd.b > 1;
      r.walked += fwd.walked;
      std::vector<BidirVertex> offset_path(fwd.path.begin(), fwd.path.begin() + fwd.alive);
      gradients::shift_camera_subpath(s, offset_path, raster + off, -off, {}, rev);
      if (rev.rejoined && rev.b == fwd.b && rev.join == fwd.join) {
        ++r.back;
        for (int k = 0; k < std::min(rev.alive, int(cam.size())); ++k)
          r.worst_p = std::max(r.worst_p, double((rev.path[size_t(k)].sp.p - cam[size_t(k)].sp.p).norm()));
        // Every vertex the Jacobian at b depends on: x_b .. x_join (and their neighbours).
        const int n = std::min(fwd.join + 1, fwd.alive - 1);
        const double bound = bidir_jj_tolerance(pointers(cam, n + 1), pointers(rev.path, n + 1), 1, n);
        r.jac(std::abs(fwd.jacobian * rev.jacobian - 1.0), bound);
      }
    }
    pathspace::light_subpath(s, params, rng, light);
    for (int sl = 2; sl <= int(light.size()); ++sl) {
      const auto ras = s.camera().raster_of(light[size_t(sl - 1)].sp.p);
      if (!ras || ras->x() < 1 || ras->y() < 1 || ras->x() + 1 > kRes - 1 || ras->y() + 1 > kRes - 1) continue;
      pathspace::Connection c;  // a light-tracing contribution: x_1 seen by the camera
      if (!pathspace::connect(s, light.data(), sl, cam.data(), 1, pathspace::MisConfig{}, c)) continue;
      if (!gradients::shift_light_tracing(s, light.data(), sl, *ras, off, {}, lf)) continue;
      ++r.lt_tried;
      r.lt_walked += lf.walked;
      if (!gradients::shift_light_tracing(s, lf.light.data(), sl, *ras + off, -off, {}, lr)) continue;
      ++r.lt_back;
      // The offset light subpath: the base's vertices up to z, then (walked) chain, y_1.
      const int e = int(lf.light.size()) - 2 - (lf.walked ? int(lf.chain.steps.size()) : 0);
      for (int k = e + 1; k < sl; ++k)
        r.worst_p = std::max(r.worst_p, double((lr.light[size_t(k)].sp.p - light[size_t(k)].sp.p).norm()));
      // J = p_cam(x_1) / p_cam(y_1) holds the cosines toward the pinhole: at grazing views
      // (|cos| < 0.1) float positions alone move it by more than the tolerance.
      const auto graze = [&](const BidirVertex& v) {
        return std::abs(v.sp.ng.dot((s.camera().position() - v.sp.p).normalized())) < 0.1f;
      };
      if (graze(light[size_t(sl - 1)]) || graze(lf.light.back())) continue;
      // x_1 .. z in camera order (x_1 = light[sl-1]); the camera's own factor is exact.
      const auto xs = camera_order(light, e, sl - 1), bs = camera_order(lr.light, e, sl - 1);
      const double bound = bidir_jj_tolerance(xs, bs, 0, int(xs.size()) - 1);
      r.jac(std::abs(lf.jacobian * lr.jacobian - 1.0), 1e-4);
      if (lf.walked) r.jac(std::abs(lf.chain.start_density * lr.chain.start_density - 1.0), bound);
    }
  }
  return r;
}
}  // namespace

TEST_CASE("G-BDPT shifts are bijective: the offset shifted back is the base, Jacobians multiply to 1", "[unit]") {
  struct Case {
    const char* name;
    std::unique_ptr<scene::Scene> scene;
  };
  Case cases[] = {{"glossy+glass", glossy_glass_box()}, {"mirror+glass", test::lit_box(mirror(), glass(), kRes)}};
  for (auto& cs : cases) {
    const RoundTrip r = round_trip(*cs.scene, 3000, 9);
    std::printf("gbdpt bijectivity %-12s: camera %d shifts, %d rejoined (%d after Dirac copies, %d through a walked "
                "chain), %d shifted back; light tracing %d shifted (%d walked), %d back; worst position error %.2e, "
                "worst |J J' - 1| %.2e (%d beyond the per-sample bound, worst %.2f of it)\n",
                cs.name, r.tried, r.rejoined, r.through_dirac, r.walked, r.back, r.lt_tried, r.lt_walked, r.lt_back,
                r.worst_p, r.worst_j, r.jj_over, r.worst_ratio);
    INFO(cs.name);
    REQUIRE(r.rejoined > r.tried / 4);
    REQUIRE(r.through_dirac > 10);
    REQUIRE(r.walked > 20);
    REQUIRE(r.lt_walked > 20);
    CHECK(r.back == r.rejoined);
    CHECK(r.lt_back == r.lt_tried);
    CHECK(r.worst_p < 1e-4);
    CHECK(r.jj_over == 0);
  }
}

namespace {
// Worst |value(T x)/value(x) - 1| / eps(d_min) over every strategy of every sample in the
// furnace sphere, and the number of offsets that failed to exist.
struct FurnaceResult {
  double worst = 0;
  int64_t terms = 0, missing = 0;
};
FurnaceResult furnace_offsets(const scene::Scene& s, gradients::JacobianFault fault) {
  gradients::BidirShiftOptions opt;
  opt.fault = fault;
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
