// Light tracing splats land in the right pixel with the right value: a point light, or a
// spot light (cone sampling, smoothstep falloff edge inside the image), over a diffuse
// plane seen by the pinhole, rendered by BDPT's strategy (2, 1) alone (light
// vertex -> plane -> splat to the camera). Every pixel is tested against the analytic
// image, L(p) = (rho / pi) I(w) cos(theta) / d^2 at the plane point p seen through the pixel,
// averaged over the pixel by 16 x 16 stratified camera rays intersected with the plane
// analytically: per-pixel t-tests over independent runs (fixed seeds), Sidak-corrected
// over the 256 pixels at a family-wise 1%. Splatting to the pixel nearest the projected
// point's corner (BidirFault::splat_pixel_rounded, a half-pixel shift) must be rejected.
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/bdpt/bdpt_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/shapes/shape.h"
#include "tests/support/quiet_options.h"
#include "tests/support/welch.h"

using namespace dp;
using namespace dp::test;

namespace {
constexpr int kRes = 16, kRuns = 10;
constexpr float kAlbedo = 0.5f, kIntensity = 2.0f;
const Vec3 kLight(0.3f, 0.8f, 0.2f);

const scene::SpotEmitter kSpot(kLight, Vec3(-0.3f, -1.0f, 0.1f), Rgb::Constant(kIntensity), 35.0f, 20.0f);

Rgb intensity(bool spot, const Vec3& w) { return spot ? kSpot.intensity(w) : Rgb::Constant(kIntensity); }

std::unique_ptr<scene::Scene> plane_scene(bool spot) {
  auto s = std::make_unique<scene::Scene>();
  const int mat = s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb::Constant(kAlbedo)))));
  auto m = std::make_unique<scene::TriangleMesh>();
  m->positions = {Vec3(-5, 0, -5), Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5)};
  m->triangles = {{0, 1, 2}, {0, 2, 3}};
  m->finalize();
  m->material = mat;
  s->add_shape(std::move(m));
  if (spot) s->add_emitter(std::make_unique<scene::SpotEmitter>(kSpot));
  else s->add_emitter(std::make_unique<scene::PointEmitter>(kLight, Rgb::Constant(kIntensity)));
  scene::CameraDesc cam;
  cam.position = Vec3(0.2f, 2.0f, 1.6f);
  cam.look_at = Vec3(0, 0, 0);
  cam.fov_deg = 50.0f;
  cam.width = cam.height = kRes;
  s->set_camera(cam);
  s->commit();
  return s;
}

// Pixel average of the analytic radiance, from 16 x 16 stratified rays.
double analytic_pixel(const scene::Scene& s, bool spot, int px, int py) {
  constexpr int n = 16;
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 raster(float(px) + (float(i) + 0.5f) / n, float(py) + (float(j) + 0.5f) / n);
      const Ray r = s.camera().generate_ray(raster);
      if (!(r.d.y() < 0.0f)) continue;
      const Vec3d p = (r.o + r.d * (-r.o.y() / r.d.y())).cast<double>();
      const Vec3d l = kLight.cast<double>() - p;
      const double d = l.norm();
      const double li = double(intensity(spot, (-l / d).cast<float>()).mean());
      sum += double(kAlbedo) / kPiD * li * std::max(0.0, l.y()) / (d * d * d);
    }
  return sum / double(n * n);
}

double verdict(const scene::Scene& s, bool spot, pathspace::BidirFault fault) {
  integrators::BdptSettings settings;
  settings.only_s = 2;
  settings.only_t = 1;
  settings.mis.unweighted = true;
  settings.mis.fault = fault;
  std::vector<std::vector<double>> runs(size_t(kRes * kRes)), ref(size_t(kRes * kRes));
  for (int r = 0; r < kRuns; ++r) {
    integrators::BdptIntegrator bdpt(settings);
    const core::Image img = bdpt.render(s, quiet_options(256, 40 + uint64_t(r), 2)).layers[0].image;
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) runs[size_t(y * kRes + x)].push_back(double(img(x, y).mean()));
  }
  double rel_se = 0;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      const double a = analytic_pixel(s, spot, x, y);
      ref[size_t(y * kRes + x)] = {a, a};  // a constant: variance 0
      const Moments m = moments(runs[size_t(y * kRes + x)]);
      if (a > 0) rel_se = std::max(rel_se, std::sqrt(m.var / double(m.n)) / a);
    }
  const double worst = sidak_welch(runs, ref, 0.01);
  std::printf("bdpt light tracing (2,1), %s light, vs analytic image%s: worst |t|/crit over 256 pixels %.2f (max rel. se %.2f%%)%s\n",
              spot ? "spot" : "point", fault == pathspace::BidirFault::none ? "" : " [fault: rounded splat pixel]", worst, 100 * rel_se,
              worst > 1 ? " -> rejected" : "");
  return worst;
}
}  // namespace

TEST_CASE("bdpt: light-tracing splats reproduce the analytic image of a point- or spot-lit plane", "[stat]") {
  for (const bool spot : {false, true}) {
    const auto s = plane_scene(spot);
    CHECK(verdict(*s, spot, pathspace::BidirFault::none) < 1.0);
    CHECK(verdict(*s, spot, pathspace::BidirFault::splat_pixel_rounded) > 1.0);
  }
}
