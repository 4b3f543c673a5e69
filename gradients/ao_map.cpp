#include "gradients/ao_map.h"

#include <cmath>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "core/warp.h"

namespace dp::gradients {

AoMap::AoMap(const scene::Scene& scene, const AoMapSettings& settings) : m_scene(scene), m_opt(settings) {
  const auto& cam = scene.camera();
  m_w = cam.width();
  m_h = cam.height();
  const size_t n = size_t(m_w) * size_t(m_h);
  m_ao.assign(n, -1.0f);
  m_depth.assign(n, 0.0f);
  m_footprint.assign(n, 0.0f);
  const float image_size = float(std::max(m_w, m_h));
  const int threads = settings.threads > 0 ? settings.threads : core::hardware_threads();
  core::parallel_for(int64_t(n), threads, [&](int64_t item, int) {
    const int x = int(item % m_w), y = int(item / m_w);
    const Ray ray = cam.generate_ray(Vec2(float(x) + 0.5f, float(y) + 0.5f));
    // Angular size of one pixel around this ray (world size per unit distance).
    const Vec3 dx = cam.generate_ray(Vec2(float(x) + 1.0f, float(y) + 0.5f)).d;
    const Vec3 d0 = cam.generate_ray(Vec2(float(x), float(y) + 0.5f)).d;
    const float foot = (dx - d0).norm();
    m_footprint[size_t(item)] = foot;
    const auto hit = scene.intersect(ray);
    if (!hit) return;
    const float dist = (hit->p - ray.o).norm();
    m_depth[size_t(item)] = dist;
    // Threshold: radius * image size in pixels, each pixel `foot * dist` wide at the hit.
    const float threshold = m_opt.radius * image_size * foot * dist;
    Vec3 nrm = hit->shading.n;
    if (nrm.dot(ray.d) > 0.0f) nrm = -nrm;
    const Frame frame = Frame::from_normal(nrm);
    core::Rng rng(m_opt.seed, uint64_t(item));
    int shorter = 0;
    for (int r = 0; r < m_opt.rays; ++r) {
      const Vec3 w = frame.to_world(core::warp::square_to_cosine_hemisphere(rng.uniform2()));
      const auto h2 = scene.intersect(scene.spawn_ray(*hit, w));
      shorter += h2 && (h2->p - hit->p).norm() < threshold;
    }
    m_ao[size_t(item)] = float(shorter) / float(std::max(1, m_opt.rays));
  });
}

float AoMap::lookup(const Vec3& p) const {
  const auto raster = m_scene.camera().raster_of(p);
  if (!raster) return -1.0f;
  const int x = std::min(m_w - 1, std::max(0, int(std::floor(raster->x()))));
  const int y = std::min(m_h - 1, std::max(0, int(std::floor(raster->y()))));
  const size_t i = size_t(y) * size_t(m_w) + size_t(x);
  if (m_ao[i] < 0.0f) return -1.0f;
  const float dist = (p - m_scene.camera().position()).norm(), depth = m_depth[i];
  // Visible iff it is the primary hit up to the depth variation inside one pixel.
  if (std::abs(dist - depth) > m_opt.depth_tolerance * depth + m_footprint[i] * dist) return -1.0f;
  return m_ao[i];
}

}  // namespace dp::gradients
