#include "experiments/stress_scenes.h"

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/media/density_grid.h"

namespace dp::experiments {

namespace {

using scene::MicrofacetType;

// Parallelogram p, p+u, p+u+v, p+v; geometric normal u x v (emitting side).
std::unique_ptr<scene::TriangleMesh> quad(const Vec3& p, const Vec3& u, const Vec3& v, int material) {
  auto m = std::make_unique<scene::TriangleMesh>();
  m->positions = {p, p + u, p + u + v, p + v};
  m->triangles = {{0, 1, 2}, {0, 2, 3}};
  m->material = material;
  m->finalize();
  return m;
}

std::unique_ptr<scene::Sphere> sphere(const Vec3& c, float r, int material) {
  auto s = std::make_unique<scene::Sphere>(c, r);
  s->material = material;
  return s;
}

float lerp(float a, float b, float t) { return a + (b - a) * t; }
// Log-uniform in [a, b].
float log_uniform(core::Rng& rng, float a, float b) { return std::exp(lerp(std::log(a), std::log(b), rng.uniform())); }

struct Builder {
  scene::Scene& s;
  int diffuse(const Rgb& albedo) {
    return s.add_bsdf(scene::make_two_sided(scene::make_diffuse(scene::constant_texture(albedo))));
  }
  int conductor(float alpha) {
    scene::ConductorFresnel f;
    f.f0 = Rgb(0.95f, 0.9f, 0.8f);
    return s.add_bsdf(scene::make_two_sided(scene::make_conductor(alpha, alpha, MicrofacetType::ggx, f)));
  }
  void camera(const Vec3& pos, const Vec3& at, float fov, int res, const Vec3& up = Vec3(0, 1, 0)) {
    scene::CameraDesc c;
    c.position = pos;
    c.look_at = at;
    c.up = up;
    c.fov_deg = fov;
    c.width = c.height = res;
    s.set_camera(c);
  }
};

// Floor y = 0 over [-2, 2]^2 (normal up) and a back wall z = -2 (normal +z).
void floor_and_wall(Builder& b, int mat) {
  b.s.add_shape(quad(Vec3(-2, 0, 2), Vec3(4, 0, 0), Vec3(0, 0, -4), mat));
  b.s.add_shape(quad(Vec3(-2, 0, -2), Vec3(4, 0, 0), Vec3(0, 4, 0), mat));
}

void coincident(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f)), red = b.diffuse(Rgb(0.7f, 0.1f, 0.1f));
  floor_and_wall(b, white);
  const float eps = log_uniform(rng, 1e-6f, 1e-4f);
  b.s.add_shape(quad(Vec3(-1, eps, 1), Vec3(2, 0, 0), Vec3(0, 0, -2), red));  // z-fights with the floor
  b.s.add_shape(quad(Vec3(-1.5f, 1, -2 + eps), Vec3(1, 0, 0), Vec3(0, 1, 0), red));
  // Sliver triangle: two vertices 1e-7 apart (may be dropped as degenerate: also a case).
  auto sliver = std::make_unique<scene::TriangleMesh>();
  const Vec3 a(0.3f, 0.2f, 0.0f);
  sliver->positions = {a, a + Vec3(1e-7f, 0, 0), a + Vec3(0.5f, 0.8f, -0.2f)};
  sliver->triangles = {{0, 1, 2}};
  sliver->material = white;
  sliver->finalize();
  b.s.add_shape(std::move(sliver));
  const float r = lerp(0.2f, 0.5f, rng.uniform());
  b.s.add_shape(sphere(Vec3(-0.6f, r, 0.3f), r, white));  // touches the floor
  // Light a hair in front of the back wall, facing +z; and one above, facing down.
  b.s.add_shape(quad(Vec3(0.5f, 1.5f, -2 + 2 * eps), Vec3(0.6f, 0, 0), Vec3(0, 0.6f, 0), -1), Rgb(10, 10, 10));
  b.s.add_shape(quad(Vec3(-0.4f, 3.0f, -0.4f), Vec3(0.8f, 0, 0), Vec3(0, 0, 0.8f), -1), Rgb(6, 6, 6));
  b.camera(Vec3(0, 1.5f, 3.5f), Vec3(0, 0.6f, 0), 50, res);
}

void grazing(Builder& b, core::Rng& rng, int res) {
  const float alpha = log_uniform(rng, 0.001f, 0.3f);
  const int ground = rng.uniform() < 0.5f ? b.conductor(alpha) : b.diffuse(Rgb(0.6f, 0.6f, 0.6f));
  b.s.add_shape(quad(Vec3(-100, 0, 100), Vec3(200, 0, 0), Vec3(0, 0, -200), ground));
  const float light_elev = deg_to_rad(lerp(0.05f, 1.0f, rng.uniform()));
  const Vec3 lp(0, 50 * std::sin(light_elev), -50 * std::cos(light_elev));
  b.s.add_shape(quad(lp + Vec3(-2, -0.01f, 0), Vec3(4, 0, 0), Vec3(0, 2, 0), -1), Rgb(200, 200, 200));
  b.s.add_shape(sphere(Vec3(0.5f, 0.05f, -3), 0.05f, b.diffuse(Rgb(0.8f, 0.3f, 0.2f))));
  const float cam_h = log_uniform(rng, 1e-3f, 1e-1f);
  b.camera(Vec3(0, cam_h, 0), Vec3(0, 0, -10), 30, res);
}

void concave(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.75f, 0.75f, 0.75f));
  const int glossy = b.conductor(log_uniform(rng, 0.01f, 0.3f));
  // Corner of three walls meeting at the origin.
  b.s.add_shape(quad(Vec3(0, 0, 0), Vec3(0, 0, 2), Vec3(2, 0, 0), white));  // floor y=0, normal +y
  b.s.add_shape(quad(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), white));  // wall z=0, normal +z
  b.s.add_shape(quad(Vec3(0, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2), glossy));  // wall x=0, normal +x
  // V-groove on the floor: two planks meeting at a small angle.
  const float half = deg_to_rad(lerp(1.0f, 5.0f, rng.uniform()));
  const Vec3 apex(1.0f, 0.01f, 1.2f);
  const Vec3 d1(std::sin(half), std::cos(half), 0), d2(-std::sin(half), std::cos(half), 0);
  b.s.add_shape(quad(apex, Vec3(0, 0, 0.6f), d1 * 0.5f, glossy));
  b.s.add_shape(quad(apex, d2 * 0.5f, Vec3(0, 0, 0.6f), white));
  // Cove light hidden behind a lip near the ceiling of the corner.
  b.s.add_shape(quad(Vec3(0.05f, 1.6f, 0.05f), Vec3(0, 0, 1.2f), Vec3(0.2f, 0, 0), white));  // lip, normal -y
  b.s.add_shape(quad(Vec3(0.02f, 1.55f, 0.1f), Vec3(0, 0, 1.0f), Vec3(0, 0.04f, 0), -1), Rgb(40, 40, 40));
  b.s.add_shape(quad(Vec3(0.6f, 2.4f, 0.6f), Vec3(0.4f, 0, 0), Vec3(0, 0, 0.4f), -1), Rgb(3, 3, 3));
  b.camera(Vec3(2.6f, 1.4f, 2.6f), Vec3(0.5f, 0.4f, 0.5f), 55, res);
}

void tiny_emitter(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f));
  floor_and_wall(b, white);
  b.s.add_shape(sphere(Vec3(0.4f, 0.4f, -0.5f), 0.4f, b.conductor(log_uniform(rng, 0.001f, 0.1f))));
  for (int i = 0; i < 3; ++i) {
    const float r = log_uniform(rng, 1e-4f, 1e-3f);
    const float radiance = 1.0f / (r * r);  // constant power
    const Vec3 c(lerp(-1.5f, 1.5f, rng.uniform()), lerp(0.5f, 2.5f, rng.uniform()), lerp(-1.5f, 1.0f, rng.uniform()));
    b.s.add_shape(sphere(c, r, -1), Rgb::Constant(radiance));
  }
  const float gap = log_uniform(rng, 1e-5f, 1e-3f);
  b.s.add_emitter(std::make_unique<scene::PointEmitter>(Vec3(-1.0f, 1.0f, -2.0f + gap), Rgb(2, 2, 2)));
  b.camera(Vec3(0, 1.2f, 3.5f), Vec3(0, 0.8f, 0), 50, res);
}

void huge_emitter(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.6f, 0.6f, 0.6f));
  auto dome = std::make_unique<scene::Sphere>(Vec3(0, 0, 0), 1e4f);
  dome->flip_normals = true;
  b.s.add_shape(std::move(dome), Rgb::Constant(log_uniform(rng, 1e-3f, 1.0f)));
  b.s.add_shape(quad(Vec3(-500, 0, 500), Vec3(1000, 0, 0), Vec3(0, 0, -1000), white));
  // Quad light much larger than the objects, facing down.
  b.s.add_shape(quad(Vec3(-50, 20, -50), Vec3(100, 0, 0), Vec3(0, 0, 100), -1), Rgb::Constant(log_uniform(rng, 0.1f, 50.0f)));
  b.s.add_shape(sphere(Vec3(0, 0.5f, 0), 0.5f, b.conductor(log_uniform(rng, 0.001f, 1.0f))));
  b.s.add_shape(sphere(Vec3(1.2f, 0.3f, 0.4f), 0.3f, white));
  b.camera(Vec3(0, 1.0f, 4.0f), Vec3(0.3f, 0.4f, 0), 45, res);
}

void specular_chain(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f));
  const int mirror = b.s.add_bsdf(scene::make_mirror(scene::constant_texture(Rgb(0.95f, 0.95f, 0.95f))));
  const int glass = b.s.add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx));
  const float tilt = deg_to_rad(lerp(0.0f, 0.5f, rng.uniform()));
  b.s.add_shape(quad(Vec3(-1.5f, 0, -3), Vec3(3, 0, 0), Vec3(0, 3, 0), white));  // back wall, normal +z
  // Two mirrors facing each other (x = -1.5 and x = 1.5), almost parallel.
  b.s.add_shape(quad(Vec3(-1.5f, 0, 1), Vec3(0, 0, -4), Vec3(std::sin(tilt), 3, 0), mirror));
  b.s.add_shape(quad(Vec3(1.5f, 0, -3), Vec3(0, 0, 4), Vec3(0, 3, 0), mirror));
  b.s.add_shape(quad(Vec3(-2, 0, 2), Vec3(4, 0, 0), Vec3(0, 0, -6), white));  // floor
  b.s.add_shape(sphere(Vec3(lerp(-0.8f, 0.8f, rng.uniform()), 0.5f, -1.0f), 0.45f, glass));
  // Glass slab (two parallel faces) in front of the light.
  b.s.add_shape(quad(Vec3(-0.5f, 2.0f, -2.2f), Vec3(1, 0, 0), Vec3(0, 0, -0.6f), glass));
  b.s.add_shape(quad(Vec3(-0.5f, 1.95f, -2.8f), Vec3(1, 0, 0), Vec3(0, 0, 0.6f), glass));
  b.s.add_shape(quad(Vec3(-0.2f, 2.6f, -2.6f), Vec3(0.4f, 0, 0), Vec3(0, 0, 0.2f), -1), Rgb(50, 50, 50));
  b.s.add_shape(sphere(Vec3(-1.2f, 2.5f, 0.5f), 0.05f, -1), Rgb(200, 200, 200));
  b.camera(Vec3(0.2f, 1.3f, 2.0f), Vec3(0, 1.0f, -2.0f), 60, res);
}

void roughness(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f));
  floor_and_wall(b, white);
  const float alphas[5] = {0.001f, log_uniform(rng, 0.001f, 0.01f), log_uniform(rng, 0.01f, 0.1f), 0.3f, 1.0f};
  for (int i = 0; i < 5; ++i) {
    const float a = alphas[i];
    const float x = -1.6f + 0.8f * float(i);
    b.s.add_shape(sphere(Vec3(x, 0.3f, 0.2f), 0.3f, b.conductor(a)));
    const int rd = b.s.add_bsdf(scene::make_dielectric(1.5f, 1.0f, a, i % 2 ? MicrofacetType::ggx : MicrofacetType::beckmann));
    b.s.add_shape(sphere(Vec3(x, 0.25f, -0.8f), 0.25f, rd));
    const int rp = b.s.add_bsdf(scene::make_two_sided(
        scene::make_plastic(scene::constant_texture(Rgb(0.2f, 0.4f, 0.7f)), 1.5f, 1.0f, a, MicrofacetType::ggx)));
    b.s.add_shape(sphere(Vec3(x, 1.0f, -1.4f), 0.25f, rp));
  }
  for (int i = 0; i < 2; ++i) {
    const float exponent = i == 0 ? 1.0f : log_uniform(rng, 1e3f, 1e4f);
    const int ph = b.s.add_bsdf(scene::make_two_sided(scene::make_phong(
        scene::constant_texture(Rgb(0.3f, 0.3f, 0.3f)), scene::constant_texture(Rgb(0.6f, 0.6f, 0.6f)), exponent)));
    b.s.add_shape(quad(Vec3(-2 + 2.5f * float(i), 0.001f, 1.5f), Vec3(1.5f, 0, 0), Vec3(0, 0, -0.8f), ph));
  }
  b.s.add_shape(quad(Vec3(-0.3f, 3.0f, -0.3f), Vec3(0.6f, 0, 0), Vec3(0, 0, 0.6f), -1), Rgb(15, 15, 15));
  b.camera(Vec3(0, 1.6f, 4.0f), Vec3(0, 0.5f, -0.5f), 50, res);
}

// Participating media at extreme coefficients: a smoke ball behind an index-matched
// boundary (sigma 1e-2..1e3 per channel, some channels without scattering, |g| up to
// 0.99) holding a smaller index-matched ball of another medium (nested boundaries), a
// glass ball filled with a medium, a thin fog around everything (the camera's medium,
// unbounded: rays that leave the scene scatter far away), an area and a point light.
void media(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f));
  floor_and_wall(b, white);
  auto medium = [&](float lo, float hi) {
    scene::HomogeneousMedium m;
    for (int c = 0; c < 3; ++c) {
      m.sigma_s[c] = rng.uniform() < 0.2f ? 0.0f : log_uniform(rng, lo, hi);
      m.sigma_a[c] = rng.uniform() < 0.5f ? 0.0f : log_uniform(rng, lo, hi);
    }
    m.phase.type = scene::PhaseFunctionDesc::Type::hg;
    m.phase.g = lerp(-0.99f, 0.99f, rng.uniform());
    return b.s.add_medium(m);
  };
  const int null = b.s.add_bsdf(scene::make_null(), "none");
  const Vec3 c(-0.7f, 0.5f, -0.5f);
  auto smoke = sphere(c, 0.5f, null);
  const int smoke_medium = medium(1e-2f, 1e3f);
  smoke->interior_medium = smoke_medium;
  b.s.add_shape(std::move(smoke));
  auto inner = sphere(c + Vec3(0.1f, 0, 0), 0.25f, null);
  inner->interior_medium = medium(1e-2f, 1e2f);
  inner->exterior_medium = smoke_medium;
  b.s.add_shape(std::move(inner));
  auto glass = sphere(Vec3(0.7f, 0.4f, 0.0f), 0.4f, b.s.add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx)));
  glass->interior_medium = medium(1e-2f, 1e2f);
  b.s.add_shape(std::move(glass));
  b.s.set_camera_medium(medium(1e-4f, 1e-1f));
  b.s.add_shape(quad(Vec3(-0.4f, 2.5f, -0.4f), Vec3(0.8f, 0, 0), Vec3(0, 0, 0.8f), -1), Rgb(15, 15, 15));
  b.s.add_emitter(std::make_unique<scene::PointEmitter>(Vec3(1.0f, 1.5f, 0.8f), Rgb(3, 3, 3)));
  b.camera(Vec3(0, 1.2f, 3.5f), Vec3(0, 0.5f, -0.3f), 50, res);
}

// Grid (heterogeneous) media at extreme contrasts: an index-matched smoke ball holding an
// 8^3 grid of random densities (a third of the cells empty, a few spikes 50x the rest;
// scale sigma_t log-uniform in 1e-2..30, albedo per channel in [0, 1], some 0, |g| up to
// 0.99) beside a glass ball filled with a second grid, over a floor; an area and a point
// light. Only the integrators that render grid media run it (the others are skipped).
void grid_media(Builder& b, core::Rng& rng, int res) {
  const int white = b.diffuse(Rgb(0.7f, 0.7f, 0.7f));
  floor_and_wall(b, white);
  auto medium = [&](const Vec3& lo, const Vec3& hi) {
    auto g = std::make_shared<scene::DensityGrid>();
    g->nx = g->ny = g->nz = 8;
    g->lo = lo;
    g->hi = hi;
    g->values.resize(512);
    for (float& v : g->values) {
      const float u = rng.uniform();
      v = u < 0.33f ? 0.0f : u < 0.36f ? 50.0f * rng.uniform() : rng.uniform();
    }
    g->finalize("stress");
    scene::HomogeneousMedium m;
    const float st = log_uniform(rng, 1e-2f, 30.0f);
    for (int c = 0; c < 3; ++c) {
      const float albedo = rng.uniform() < 0.2f ? 0.0f : rng.uniform();
      m.sigma_s[c] = st * albedo;
      m.sigma_a[c] = st - m.sigma_s[c];
    }
    m.phase.type = scene::PhaseFunctionDesc::Type::hg;
    m.phase.g = lerp(-0.99f, 0.99f, rng.uniform());
    m.density = std::move(g);
    return b.s.add_medium(m);
  };
  const int null = b.s.add_bsdf(scene::make_null(), "none");
  const Vec3 c(-0.6f, 0.55f, -0.4f);
  auto smoke = sphere(c, 0.5f, null);
  smoke->interior_medium = medium(c - Vec3::Constant(0.5f), c + Vec3::Constant(0.5f));
  b.s.add_shape(std::move(smoke));
  const Vec3 gc(0.7f, 0.4f, 0.0f);
  auto glass = sphere(gc, 0.4f, b.s.add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx)));
  glass->interior_medium = medium(gc - Vec3::Constant(0.4f), gc + Vec3::Constant(0.4f));
  b.s.add_shape(std::move(glass));
  b.s.add_shape(quad(Vec3(-0.4f, 2.5f, -0.4f), Vec3(0.8f, 0, 0), Vec3(0, 0, 0.8f), -1), Rgb(15, 15, 15));
  b.s.add_emitter(std::make_unique<scene::PointEmitter>(Vec3(1.0f, 1.5f, 0.8f), Rgb(3, 3, 3)));
  b.camera(Vec3(0, 1.2f, 3.5f), Vec3(0, 0.5f, -0.3f), 50, res);
}

}  // namespace

std::vector<std::string> stress_families() {
  return {"coincident", "grazing", "concave", "tiny_emitter", "huge_emitter", "specular_chain", "roughness", "media",
          "grid_media"};
}

StressScene make_stress_scene(const std::string& family, int variant, uint64_t seed, int resolution) {
  StressScene out;
  out.family = family;
  out.variant = variant;
  out.scene = std::make_unique<scene::Scene>();
  out.scene->set_source("stress:" + family + "#" + std::to_string(variant));
  const auto families = stress_families();
  uint64_t family_index = 0;
  while (family_index < families.size() && families[family_index] != family) ++family_index;
  if (family_index == families.size()) throw ValueError("unknown stress scene family '" + family + "'");
  core::Rng rng(seed, family_index * 1000003ull + uint64_t(variant));
  Builder b{*out.scene};
  switch (family_index) {
    case 0: coincident(b, rng, resolution); break;
    case 1: grazing(b, rng, resolution); break;
    case 2: concave(b, rng, resolution); break;
    case 3: tiny_emitter(b, rng, resolution); break;
    case 4: huge_emitter(b, rng, resolution); break;
    case 5: specular_chain(b, rng, resolution); out.max_depth = 32; break;
    case 6: roughness(b, rng, resolution); break;
    case 7: media(b, rng, resolution); out.max_depth = 16; break;
    default: grid_media(b, rng, resolution); out.max_depth = 16; break;
  }
  out.scene->commit();
  return out;
}

}  // namespace dp::experiments
