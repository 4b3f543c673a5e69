// Per-pixel feature buffers for structure-adaptive kernels (Manzi et al. 2014, Sec. 3.5
// "Pixel affinity" and Sec. 4 "Structure-Adaptive Gradients": normals, depth and
// texture gathered from primary hits, "normalized to range [0, 1]" (Sec. 5)).
//
// render_features traces `spp` primary rays per pixel, jittered uniformly inside the
// pixel (box filter, camera.h raster convention) and averages, per pixel:
//   normal  the first hit's shading normal, flipped to face the ray (a unit vector);
//   albedo  Bsdf::albedo(uv) at the hit (diffuse reflectance / texture value; 0 for a
//           hit without a BSDF, e.g. a bare emitter);
//   depth   the hit distance along the unit ray direction (world units).
// A miss (or a sample with a non-finite value) contributes normal 0, albedo 0 and the
// largest hit distance found anywhere in the image (0 if nothing is hit): the
// background sits as far away as the farthest surface.
// Then each feature is mapped affinely to [0, 1] over the whole image with one scale
// shared by its channels (min and max over all pixels and channels), so squared
// distances between vector features keep their geometry. A feature that is constant
// over the image maps to 0.
//
// Deterministic for a given seed and any thread count: image row y draws from
// core::Rng(seed, y) whatever thread renders it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace dp::scene {
class Scene;
}

namespace dp::kernels_adaptive {

struct Features {
  int width = 0, height = 0;
  // One value per pixel, index y * width + x, each in [0, 1] after render_features.
  std::vector<Vec3> normal;
  std::vector<Rgb> albedo;
  std::vector<float> depth;

  size_t pixels() const { return size_t(width) * size_t(height); }
};

// Throws dp::ValueError for spp < 1. threads = 0: all hardware threads.
Features render_features(const scene::Scene& scene, int spp, uint64_t seed, int threads);

// Maps every feature of `f` to [0, 1] as described above (in place). render_features
// calls it; exposed for features filled by other means (tests, loaded buffers).
void normalize_features(Features& f);

// Throws dp::ValueError unless every buffer has width * height entries (width, height > 0).
void validate(const Features& f);

}  // namespace dp::kernels_adaptive
