// Path-tracer throughput vs a bare Embree ray loop tracing the same number of rays.
// Usage: bench_pt SCENE.yaml... [--spp N] [--threads T]
// For each scene: PT renders N spp; its ray counts (intersect + shadow) are replayed by
// a bare loop: camera rays, then cosine-distributed bounces off Embree's geometric
// normal and one shadow ray per hit toward a random point of the scene bounds, with no
// shading, no BSDFs and no image. Ratio = bare time / PT time (1 = PT is as fast as
// tracing its rays). Prints one CSV row per scene.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "core/warp.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"
#include "manifold/mesh_normals.h"
#include "scene/embree_accel.h"
#include "scene/loaders/loader.h"

using namespace dp;

namespace {
struct Counts {
  int64_t rays = 0, shadow = 0;
};

double bare_loop(const scene::Scene& s, Counts target, int threads) {
  const auto& cam = s.camera();
  const auto& accel = s.accel();
  const Bounds3 b = s.bounds();
  core::Timer timer;
  const int64_t chunks = 256;
  core::parallel_for(chunks, threads, [&](int64_t chunk, int) {
    core::Rng rng(99, uint64_t(chunk));
    int64_t rays = target.rays / chunks, shadow = target.shadow / chunks;
    while (rays > 0) {
      Ray ray = cam.generate_ray(Vec2(rng.uniform() * float(cam.width()), rng.uniform() * float(cam.height())));
      for (int depth = 0; depth < 8 && rays > 0; ++depth) {
        scene::RawHit hit;
        --rays;
        if (!accel.intersect(ray, hit)) break;
        const Vec3 p = ray.at(hit.t);
        Vec3 n = hit.ng.normalized();
        if (n.dot(ray.d) > 0) n = -n;
        const Vec3 origin = p + n * scene::Scene::epsilon_at(p);
        if (shadow > 0) {
          const Vec3 target_p = b.lo + (b.hi - b.lo).cwiseProduct(Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
          Ray sr{origin, (target_p - origin).normalized(), 0.0f, (target_p - origin).norm()};
          accel.occluded(sr);
          --shadow;
        }
        ray = Ray{origin, Frame::from_normal(n).to_world(core::warp::square_to_cosine_hemisphere(rng.uniform2())), 0.0f, kInfinity};
      }
    }
  });
  return timer.seconds();
}
}  // namespace

int main(int argc, char** argv) {
  int spp = 16, threads = 0;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--spp") && i + 1 < argc) spp = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else scenes.emplace_back(argv[i]);
  }
  std::printf("scene,resolution,spp,threads,pt_seconds,paths_per_second,rays,shadow_rays,bare_seconds,pt_vs_bare\n");
  for (const auto& path : scenes) {
    const auto s = scene::load_scene(path, {manifold::normal_estimation_hook()});
    integrators::Settings settings;
    auto pt = integrators::make_integrator("path", settings);
    integrators::RenderOptions opt;
    opt.spp = spp;
    opt.threads = threads;
    opt.quiet = true;
    opt.max_depth = s->integrator_defaults().max_depth;
    const auto r = pt->render(*s, opt);
    Counts c{r.stats.get("pt.rays"), r.stats.get("pt.shadow_rays")};
    const int t = integrators::resolve_threads(opt);
    const double bare = bare_loop(*s, c, t);
    const double paths = double(r.stats.get("pt.paths"));
    std::printf("%s,%dx%d,%d,%d,%.3f,%.0f,%lld,%lld,%.3f,%.3f\n", path.c_str(), s->camera().width(), s->camera().height(),
                spp, t, r.wall_seconds, paths / r.wall_seconds, (long long)c.rays, (long long)c.shadow, bare,
                bare / r.wall_seconds);
  }
  return 0;
}
