// Scene build time (TriangleMesh::finalize + Embree BVH) for a procedurally generated
// mesh of about N triangles (default 1M): a displaced grid, so the BVH is non-trivial.
// Usage: bench_build [triangles]
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/timer.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/scene.h"

using namespace dp;

int main(int argc, char** argv) {
  const long target = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int n = int(std::sqrt(double(target) / 2.0));  // n x n quads = 2 n^2 triangles
  auto mesh = std::make_unique<scene::TriangleMesh>();
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const float u = float(x) / float(n), v = float(y) / float(n);
      mesh->positions.emplace_back(u, 0.1f * std::sin(20.0f * u) * std::cos(17.0f * v), v);
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      mesh->triangles.push_back({a, b, d});
      mesh->triangles.push_back({a, d, c});
    }
  core::Timer timer;
  mesh->finalize();
  const double finalize_s = timer.seconds();
  scene::Scene s;
  mesh->material = s.add_bsdf(scene::make_diffuse(scene::constant_texture(Rgb::Constant(0.5f))));
  s.add_shape(std::move(mesh));
  scene::CameraDesc cam;
  cam.position = Vec3(0.5f, 2, 0.5f);
  cam.look_at = Vec3(0.5f, 0, 0.5f);
  cam.up = Vec3(0, 0, 1);
  s.set_camera(cam);
  timer.reset();
  s.commit();
  const double commit_s = timer.seconds();
  std::printf("triangles,finalize_seconds,bvh_seconds\n%zu,%.3f,%.3f\n", s.triangle_count(), finalize_s, commit_s);
  return 0;
}
