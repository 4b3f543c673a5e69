// Shared by the density-estimation tests in media (test_vpm_bre, test_gvpm, test_beam):
// their channel means (render options: tests/support/quiet_options.h), the
// volumetric furnace's medium and environment, per-run statistics, and the camera rays'
// mean length in the furnace ball's outer shell (the extent of the kernels' boundary bias).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/image.h"
#include "core/rng.h"
#include "integrators/integrator.h"
#include "tests/support/quiet_options.h"  // quiet_options: the render options of these tests
#include "scene/scene.h"

namespace dp::test {

inline double channel_mean(const core::Image& img, int c) {
  double s = 0;
  for (const auto& p : img.pixels()) s += double(p[c]);
  return s / double(img.size());
}

// [statistic][run]
using Runs = std::vector<std::vector<double>>;
inline void add_run(Runs& runs, const std::vector<double>& values) {
  runs.resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) runs[i].push_back(values[i]);
}

// (test_gvpm, test_gvpm_chain)
// Per run: the image mean (summed channels), then per block x block the mean of the forward
// differences in x and in y (summed channels) over the block's pixels whose neighbour
// exists -- from `dx`/`dy` layers plus the pixel differences of the unshifted `direct`
// layer (gvpm's gradients cover only the primary ray's gathers), or from the image's own
// pixel differences (dx, dy null: volpath).
inline std::vector<double> gradient_blocks(const core::Image& img, const core::Image* dx, const core::Image* dy,
                                           const core::Image* direct, int block) {
  const int w = img.width(), h = img.height();
  std::vector<double> out;
  double total = 0;
  for (const auto& p : img.pixels()) total += double(p.sum());
  out.push_back(total / double(img.size()));
  for (int axis = 0; axis < 2; ++axis)
    for (int by = 0; by < h / block; ++by)
      for (int bx = 0; bx < w / block; ++bx) {
        double s = 0;
        int n = 0;
        for (int y = by * block; y < (by + 1) * block; ++y)
          for (int x = bx * block; x < (bx + 1) * block; ++x) {
            const int qx = x + (axis == 0), qy = y + (axis == 1);
            if (qx >= w || qy >= h) continue;
            const core::Image* g = axis == 0 ? dx : dy;
            s += g ? double((*g)(x, y).sum()) + double((*direct)(qx, qy).sum() - (*direct)(x, y).sum())
                   : double(img(qx, qy).sum() - img(x, y).sum());
            ++n;
          }
        out.push_back(s / double(n));
      }
  return out;
}

// Albedo 1, spectrally varying density, forward-scattering HG: the furnace ball's medium.
inline scene::HomogeneousMedium furnace_medium() {
  scene::HomogeneousMedium m;
  m.sigma_a = Rgb::Zero();
  m.sigma_s = Rgb(0.5f, 1.0f, 2.0f);
  m.phase.type = scene::PhaseFunctionDesc::Type::hg;
  m.phase.g = 0.6f;
  return m;
}
inline const Rgb kFurnaceEnv(1.0f, 0.8f, 0.6f);

// Mean over the image (16 random rays per pixel) of the camera ray's length inside the
// shell R - r < |x| < R of the furnace ball (R = 1 at the origin).
inline double shell_length(const scene::Scene& s, double r) {
  const auto& cam = s.camera();
  core::Rng rng(77, 0);
  auto inside = [](const Ray& ray, double radius) {
    const double b = double(ray.o.dot(ray.d)), c = double(ray.o.squaredNorm()) - radius * radius;
    const double disc = b * b - c;
    if (disc <= 0) return 0.0;
    const double t0 = std::max(0.0, -b - std::sqrt(disc)), t1 = -b + std::sqrt(disc);
    return std::max(0.0, t1 - t0);
  };
  double sum = 0;
  int n = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x)
      for (int k = 0; k < 16; ++k, ++n) {
        const Ray ray = cam.generate_ray(Vec2(float(x) + rng.uniform(), float(y) + rng.uniform()));
        sum += inside(ray, 1.0) - inside(ray, std::max(0.0, 1.0 - r));
      }
  return sum / n;
}

}  // namespace dp::test
