#include "tests/support/test_scenes.h"

#include <array>

#include "scene/bsdf/bsdfs.h"

namespace dp::test {

namespace {
std::unique_ptr<scene::TriangleMesh> quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  auto m = std::make_unique<scene::TriangleMesh>();
  m->positions = {a, b, c, d};
  m->triangles = {{0, 1, 2}, {0, 2, 3}};
  m->finalize();
  return m;
}

// The walls of the box [-1,1]^3 with materials floor, ceiling, left, right, back, front.
void add_box(scene::Scene& s, const std::array<int, 6>& mat) {
  const Vec3 p[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const int q[6][4] = {{0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  for (int w = 0; w < 6; ++w) {
    auto m = quad(p[q[w][0]], p[q[w][1]], p[q[w][2]], p[q[w][3]]);
    m->material = mat[size_t(w)];
    s.add_shape(std::move(m));
  }
}

// Square-image camera, then commit: the last step of every test scene.
std::unique_ptr<scene::Scene> finish(std::unique_ptr<scene::Scene> s, const Vec3& position, const Vec3& look_at,
                                     float fov_deg, int resolution) {
  scene::CameraDesc cam;
  cam.position = position;
  cam.look_at = look_at;
  cam.fov_deg = fov_deg;
  cam.width = cam.height = resolution;
  s->set_camera(cam);
  s->commit();
  return s;
}
}  // namespace

double furnace_radiance(float albedo, float emission, float point_intensity) {
  const double a = albedo;
  return double(emission) / (1.0 - a) + a * double(point_intensity) / (kPiD * (1.0 - a));
}

std::unique_ptr<scene::Scene> furnace_sphere(float albedo, float emission, float point_intensity, int resolution) {
  auto s = std::make_unique<scene::Scene>();
  const int mat = s->add_bsdf(scene::make_diffuse(scene::constant_texture(Rgb::Constant(albedo))), "wall");
  auto sphere = std::make_unique<scene::Sphere>(Vec3(0, 0, 0), 1.0f);
  sphere->flip_normals = true;
  sphere->material = mat;
  s->add_shape(std::move(sphere), Rgb::Constant(emission));
  if (point_intensity > 0)
    s->add_emitter(std::make_unique<scene::PointEmitter>(Vec3(0, 0, 0), Rgb::Constant(point_intensity)));
  return finish(std::move(s), Vec3(0.1f, 0.2f, 0.3f), Vec3(0.5f, 0.1f, -1.0f), 90.0f, resolution);
}

// The white box with a red wall and the ceiling light facing down, slightly below the
// ceiling (lit_box, media_box, grid_media_box); `white`: the walls' BSDF index.
namespace {
std::unique_ptr<scene::Scene> lit_box_shell(int& white) {
  auto s = std::make_unique<scene::Scene>();
  white = s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb(0.7f, 0.7f, 0.7f)))));
  const int red = s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb(0.7f, 0.1f, 0.1f)))));
  add_box(*s, {white, white, red, white, white, white});
  auto light = quad(Vec3(-0.3f, 0.98f, -0.3f), Vec3(0.3f, 0.98f, -0.3f), Vec3(0.3f, 0.98f, 0.3f), Vec3(-0.3f, 0.98f, 0.3f));
  s->add_shape(std::move(light), Rgb(8, 8, 8));
  return s;
}
}  // namespace

std::unique_ptr<scene::Scene> lit_box(scene::BsdfPtr sphere_a, scene::BsdfPtr sphere_b, int resolution) {
  int white = -1;
  auto s = lit_box_shell(white);
  auto sa = std::make_unique<scene::Sphere>(Vec3(-0.45f, -0.6f, -0.2f), 0.4f);
  sa->material = sphere_a ? s->add_bsdf(sphere_a) : white;
  s->add_shape(std::move(sa));
  auto sb = std::make_unique<scene::Sphere>(Vec3(0.45f, -0.6f, 0.2f), 0.4f);
  sb->material = sphere_b ? s->add_bsdf(sphere_b) : white;
  s->add_shape(std::move(sb));
  return finish(std::move(s), Vec3(0, 0, 0.95f), Vec3(0, 0, -1), 80.0f, resolution);
}

namespace {
scene::HomogeneousMedium make_medium(const Rgb& sigma_a, const Rgb& sigma_s, float g);
}  // namespace

std::unique_ptr<scene::Scene> caustic_box(int resolution, bool fog) {
  auto s = std::make_unique<scene::Scene>();
  const int white = s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb(0.7f, 0.7f, 0.7f)))));
  const int black = s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb::Zero()))));
  add_box(*s, {white, black, black, black, black, black});
  auto add = [&](std::unique_ptr<scene::TriangleMesh> m, int mat) {
    m->material = mat;
    s->add_shape(std::move(m));
  };
  // The shelf at y = 0.3 around the opening |x|, |z| <= 0.25.
  constexpr float y = 0.3f, h = 0.25f;
  auto shelf = [&](float x0, float x1, float z0, float z1) {
    add(quad(Vec3(x0, y, z0), Vec3(x1, y, z0), Vec3(x1, y, z1), Vec3(x0, y, z1)), black);
  };
  shelf(-1, 1, h, 1);
  shelf(-1, 1, -1, -h);
  shelf(-1, -h, -h, h);
  shelf(h, 1, -h, h);
  auto light = quad(Vec3(-0.3f, 0.98f, -0.3f), Vec3(0.3f, 0.98f, -0.3f), Vec3(0.3f, 0.98f, 0.3f), Vec3(-0.3f, 0.98f, 0.3f));
  s->add_shape(std::move(light), Rgb(8, 8, 8));
  auto glass = std::make_unique<scene::Sphere>(Vec3(0.0f, y, 0.0f), 0.4f);
  glass->material = s->add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx));
  s->add_shape(std::move(glass));
  if (fog) s->set_camera_medium(s->add_medium(make_medium(Rgb::Constant(0.05f), Rgb::Constant(0.4f), 0.0f)));
  return finish(std::move(s), Vec3(0.0f, -0.1f, 0.95f), Vec3(0.0f, -1.0f, -0.2f), 70.0f, resolution);
}

std::unique_ptr<scene::Scene> env_glossy(scene::BsdfPtr sphere, int resolution, float sun) {
  auto s = std::make_unique<scene::Scene>();
  const int grey =
      s->add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(Rgb(0.5f, 0.5f, 0.5f)))));
  auto floor = quad(Vec3(-3, -1, -4), Vec3(-3, -1, 2), Vec3(3, -1, 2), Vec3(3, -1, -4));
  floor->material = grey;
  s->add_shape(std::move(floor));
  auto big = std::make_unique<scene::Sphere>(Vec3(0.0f, -0.4f, -1.3f), 0.6f);
  big->material = sphere ? s->add_bsdf(sphere) : grey;
  s->add_shape(std::move(big));
  auto small = std::make_unique<scene::Sphere>(Vec3(0.75f, -0.75f, -0.75f), 0.25f);
  small->material = grey;
  s->add_shape(std::move(small));
  core::Image map(32, 16);
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x)
      map(x, y) = (x / 4 + y / 4) % 2 == 0 ? Rgb(1.6f, 1.4f, 1.0f) : Rgb(0.15f, 0.2f, 0.3f);
  s->add_emitter(std::make_unique<scene::EnvironmentEmitter>(std::move(map), Mat3::Identity(), 1.0f));
  if (sun > 0.0f) s->add_emitter(std::make_unique<scene::DirectionalEmitter>(Vec3(0.4f, -1.0f, -0.3f), Rgb::Constant(sun)));
  return finish(std::move(s), Vec3(0.0f, 0.0f, 0.6f), Vec3(0.0f, -0.45f, -1.3f), 50.0f, resolution);
}

namespace {
scene::HomogeneousMedium make_medium(const Rgb& sigma_a, const Rgb& sigma_s, float g) {
  scene::HomogeneousMedium m;
  m.sigma_a = sigma_a;
  m.sigma_s = sigma_s;
  m.phase.type = scene::PhaseFunctionDesc::Type::hg;
  m.phase.g = g;
  return m;
}
}  // namespace

std::unique_ptr<scene::Scene> medium_furnace(const scene::HomogeneousMedium& medium, const Rgb& env, bool camera_inside,
                                             int resolution) {
  auto s = std::make_unique<scene::Scene>();
  const int m = s->add_medium(medium);
  auto ball = std::make_unique<scene::Sphere>(Vec3(0, 0, 0), 1.0f);
  ball->material = s->add_bsdf(scene::make_null(), "none");
  ball->interior_medium = m;
  scene::Sphere* ball_ptr = ball.get();
  s->add_shape(std::move(ball));
  s->add_emitter(std::make_unique<scene::EnvironmentEmitter>(env));
  if (camera_inside) {
    // The camera's medium is the ball's; the outside would default to it too
    // (SCENE_FORMAT.md), so the ball names a clear exterior (no extinction: vacuum).
    ball_ptr->exterior_medium = s->add_medium(scene::HomogeneousMedium{});
    s->set_camera_medium(m);
    return finish(std::move(s), Vec3(0.0f, 0.1f, 0.3f), Vec3(0.2f, 0.0f, -1.0f), 80.0f, resolution);
  }
  return finish(std::move(s), Vec3(0.0f, 0.0f, 2.5f), Vec3(0, 0, 0), 55.0f, resolution);
}

std::unique_ptr<scene::Scene> media_box(bool fog, int resolution, bool glass_ball, bool point_light) {
  int white = -1;
  auto s = lit_box_shell(white);
  auto smoke = std::make_unique<scene::Sphere>(Vec3(-0.45f, -0.6f, -0.2f), 0.4f);
  smoke->material = s->add_bsdf(scene::make_null(), "none");
  smoke->interior_medium = s->add_medium(make_medium(Rgb::Constant(0.2f), Rgb(1.5f, 2.5f, 3.5f), 0.5f));
  s->add_shape(std::move(smoke));
  auto glass = std::make_unique<scene::Sphere>(Vec3(0.45f, -0.6f, 0.2f), 0.4f);
  if (glass_ball) {
    glass->material = s->add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx));
    glass->interior_medium = s->add_medium(make_medium(Rgb(0.2f, 0.8f, 1.6f), Rgb::Constant(0.3f), 0.0f));
  } else {
    glass->material = white;
  }
  s->add_shape(std::move(glass));
  if (fog) s->set_camera_medium(s->add_medium(make_medium(Rgb::Constant(0.05f), Rgb::Constant(0.15f), -0.3f)));
  if (point_light) s->add_emitter(std::make_unique<scene::PointEmitter>(Vec3(0.0f, -0.1f, -0.3f), Rgb(0.3f, 0.25f, 0.2f)));
  return finish(std::move(s), Vec3(0, 0, 0.95f), Vec3(0, 0, -1), 80.0f, resolution);
}

namespace {
// A grid medium of grey extinction sigma_t at density 1 with the given albedo.
scene::HomogeneousMedium grid_medium(const scene::DensityGrid& g, float sigma_t, const Rgb& albedo, float phase_g) {
  scene::HomogeneousMedium m = make_medium(sigma_t * (Rgb::Ones() - albedo), sigma_t * albedo, phase_g);
  m.density = std::make_shared<scene::DensityGrid>(g);
  return m;
}
}  // namespace

std::unique_ptr<scene::Scene> grid_media_box(int resolution) {
  int white = -1;
  auto s = lit_box_shell(white);
  const Vec3 c(-0.45f, -0.6f, -0.2f);
  scene::DensityGrid ramp;
  ramp.nx = ramp.ny = ramp.nz = 3;
  ramp.lo = c - Vec3::Constant(0.4f);
  ramp.hi = c + Vec3::Constant(0.4f);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) ramp.values.push_back(float(x));
  ramp.finalize("grid_media_box");
  auto smoke = std::make_unique<scene::Sphere>(c, 0.4f);
  smoke->material = s->add_bsdf(scene::make_null(), "none");
  smoke->interior_medium = s->add_medium(grid_medium(ramp, 2.0f, Rgb(0.9f, 0.7f, 0.5f), 0.5f));
  s->add_shape(std::move(smoke));
  auto glass = std::make_unique<scene::Sphere>(Vec3(0.45f, -0.6f, 0.2f), 0.4f);
  glass->material = s->add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx));
  glass->interior_medium = s->add_medium(make_medium(Rgb(0.2f, 0.8f, 1.6f), Rgb::Constant(0.3f), 0.0f));
  s->add_shape(std::move(glass));
  scene::DensityGrid fog;
  fog.nx = fog.ny = fog.nz = 5;
  fog.lo = Vec3::Constant(-1.0f);
  fog.hi = Vec3::Constant(1.0f);
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 5; ++x) fog.values.push_back(0.5f + 0.25f * float((x + 2 * y + 3 * z) % 5));
  fog.finalize("grid_media_box");
  s->set_camera_medium(s->add_medium(grid_medium(fog, 0.2f, Rgb::Constant(0.75f), -0.3f)));
  return finish(std::move(s), Vec3(0, 0, 0.95f), Vec3(0, 0, -1), 80.0f, resolution);
}

}  // namespace dp::test
