#include "kernels_adaptive/features.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "core/thread_pool.h"
#include "scene/scene.h"

namespace dp::kernels_adaptive {

namespace {

// Shared affine map of n-channel values to [0, 1]: (v - lo) / (hi - lo).
template <typename T>
void normalize_channels(std::vector<T>& values, int channels) {
  float lo = kInfinity, hi = -kInfinity;
  for (const T& v : values)
    for (int c = 0; c < channels; ++c) {
      lo = std::min(lo, v[c]);
      hi = std::max(hi, v[c]);
    }
  const float range = hi - lo;
  for (T& v : values)
    for (int c = 0; c < channels; ++c)
      v[c] = (range > 0.0f && std::isfinite(range)) ? std::clamp((v[c] - lo) / range, 0.0f, 1.0f) : 0.0f;
}

}  // namespace

void validate(const Features& f) {
  const size_t n = f.pixels();
  if (f.width <= 0 || f.height <= 0 || f.normal.size() != n || f.albedo.size() != n || f.depth.size() != n)
    throw ValueError("kernels_adaptive: feature buffers of " + std::to_string(f.width) + "x" +
                     std::to_string(f.height) + " need width * height > 0 entries each");
}

void normalize_features(Features& f) {
  validate(f);
  normalize_channels(f.normal, 3);
  normalize_channels(f.albedo, 3);
  float lo = kInfinity, hi = -kInfinity;
  for (float d : f.depth) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const float range = hi - lo;
  for (float& d : f.depth) d = (range > 0.0f && std::isfinite(range)) ? std::clamp((d - lo) / range, 0.0f, 1.0f) : 0.0f;
}

Features render_features(const scene::Scene& scene, int spp, uint64_t seed, int threads) {
  if (spp < 1) throw ValueError("kernels_adaptive: render_features needs spp >= 1, got " + std::to_string(spp));
  const auto& cam = scene.camera();
  Features f;
  f.width = cam.width();
  f.height = cam.height();
  const size_t n = f.pixels();
  f.normal.assign(n, Vec3::Zero());
  f.albedo.assign(n, Rgb::Zero());
  f.depth.assign(n, 0.0f);
  std::vector<int> misses(n, 0);
  std::vector<double> depth_sum(n, 0.0);
  std::vector<float> row_max_depth(size_t(f.height), 0.0f);
  const int workers = threads > 0 ? threads : core::hardware_threads();

  // Sums per pixel; one Rng per image row (determinism independent of scheduling).
  core::parallel_for(f.height, workers, [&](int64_t item, int) {
    const int y = int(item);
    core::Rng rng(seed, uint64_t(y));
    scene::SurfaceHit hit;
    for (int x = 0; x < f.width; ++x) {
      const size_t i = size_t(y) * size_t(f.width) + size_t(x);
      Vec3 nsum = Vec3::Zero();
      Rgb asum = Rgb::Zero();
      double dsum = 0.0;
      for (int s = 0; s < spp; ++s) {
        const Vec2 u = rng.uniform2();
        const Ray ray = cam.generate_ray(Vec2(float(x) + u.x(), float(y) + u.y()));
        if (!scene.intersect(ray, hit)) {
          ++misses[i];
          continue;
        }
        Vec3 normal = hit.shading.n;
        if (normal.dot(ray.d) > 0.0f) normal = -normal;  // face the viewer
        scene::BsdfContext ctx;
        ctx.uv = hit.uv;
        const Rgb albedo = hit.bsdf ? hit.bsdf->albedo(ctx) : Rgb::Zero();
        if (!normal.allFinite() || !albedo.allFinite() || !std::isfinite(hit.t)) {
          ++misses[i];
          continue;
        }
        nsum += normal;
        asum += albedo;
        dsum += double(hit.t);
        row_max_depth[size_t(y)] = std::max(row_max_depth[size_t(y)], hit.t);
      }
      f.normal[i] = nsum / float(spp);
      f.albedo[i] = asum / float(spp);
      depth_sum[i] = dsum;  // misses are added below, once the farthest hit is known
    }
  });

  const float far = *std::max_element(row_max_depth.begin(), row_max_depth.end());
  for (size_t i = 0; i < n; ++i) f.depth[i] = float((depth_sum[i] + double(misses[i]) * double(far)) / double(spp));
  normalize_features(f);
  return f;
}

}  // namespace dp::kernels_adaptive
