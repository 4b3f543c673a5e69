// Shared by the `plane` tests (test_plane.cpp, test_plane_render.cpp): the render call with a
// planted defect, the image mean, random directions, and the occluded furnace scene.
#pragma once

#include <memory>

#include "core/rng.h"
#include "core/warp.h"
#include "integrators/plane/plane_integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/integrators/media_furnace_support.h"

namespace dp::test {

inline Vec3 random_direction(core::Rng& rng) { return core::warp::square_to_uniform_sphere(rng.uniform2()); }

inline integrators::RenderResult render_plane(const scene::Scene& s, integrators::PlaneFault fault, int photons,
                                              int iterations, uint64_t seed, int max_depth,
                                              double radius_scale = 0.01) {
  integrators::PlaneSettings p;
  p.photons = photons;
  p.radius_scale = radius_scale;  // the beam part's (test_beam's 0.01 by default)
  p.fault = fault;
  return integrators::PlaneIntegrator(p).render(s, test::quiet_options(iterations, seed, max_depth));
}

inline double image_mean(const core::Image& img) {
  double s = 0;
  for (const auto& p : img.pixels()) s += double(p.sum());
  return s / double(img.size());
}

// The furnace ball (camera outside, environment light) with an opaque black ball of radius
// 0.75 at its centre: light crossing the centre is blocked, so planes must test a1(t0) -> b.
inline std::unique_ptr<scene::Scene> occluded_furnace(int resolution) {
  auto s = std::make_unique<scene::Scene>();
  const int m = s->add_medium(furnace_medium());
  auto ball = std::make_unique<scene::Sphere>(Vec3(0, 0, 0), 1.0f);
  ball->material = s->add_bsdf(scene::make_null(), "none");
  ball->interior_medium = m;
  s->add_shape(std::move(ball));
  auto core = std::make_unique<scene::Sphere>(Vec3(0, 0, 0), 0.75f);
  core->material = s->add_bsdf(scene::make_diffuse(scene::constant_texture(Rgb::Zero())), "black");
  core->exterior_medium = m;
  s->add_shape(std::move(core));
  s->add_emitter(std::make_unique<scene::EnvironmentEmitter>(kFurnaceEnv));
  scene::CameraDesc cam;
  cam.position = Vec3(0.0f, 0.0f, 2.5f);
  cam.look_at = Vec3(0, 0, 0);
  cam.fov_deg = 55.0f;
  cam.width = cam.height = resolution;
  s->set_camera(cam);
  s->commit();
  return s;
}

}  // namespace dp::test
