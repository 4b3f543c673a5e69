#include "integrators/kernel_footprint.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/vcm_mis.h"

namespace dp::integrators {

using pathspace::BidirVertex;

double footprint_radius(const scene::Scene& scene, const BidirVertex* path, int k) {
  const scene::PerspectiveCamera& cam = scene.camera();
  const Vec3 w0 = -path[1].wi;
  const double pdf = double(cam.pdf_direction(w0));
  double D = 0;
  for (int i = 1; i <= k; ++i) D += double((path[i].sp.p - path[i - 1].sp.p).norm());
  const double cos_k = std::max(0.1, std::abs(double(path[k].sp.ng.dot(path[k].wi))));
  const double omega = 1.0 / (pdf * double(cam.width()) * double(cam.height()));
  return pdf > 0 ? D * std::sqrt(omega / (kPiD * cos_k)) : 0.0;
}

double median_footprint(const scene::Scene& scene, int max_depth, int rr_depth) {
  const auto& cam = scene.camera();
  const int step_x = std::max(1, cam.width() / 32), step_y = std::max(1, cam.height() / 32);
  pathspace::SubpathParams params{max_depth + 1, rr_depth};
  params.stop_after_smooth = true;
  core::Rng rng(0x5eed, 17);
  std::vector<pathspace::BidirVertex> path;
  std::vector<double> r;
  for (int y = step_y / 2; y < cam.height(); y += step_y)
    for (int x = step_x / 2; x < cam.width(); x += step_x) {
      pathspace::camera_subpath(scene, Vec2(float(x) + 0.5f, float(y) + 0.5f), params, rng, path);
      for (int k = 1; k < int(path.size()); ++k)
        if (!path[size_t(k)].delta) {
          if (pathspace::vcm_mergeable(path[size_t(k)], false)) r.push_back(footprint_radius(scene, path.data(), k));
          break;
        }
    }
  if (r.empty()) return 0.0;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return r[r.size() / 2];
}

double first_radius(const scene::Scene& scene, int max_depth, int rr_depth, double scale) {
  const double footprint = median_footprint(scene, max_depth, rr_depth);
  return scale * (footprint > 0 ? footprint : 0.003 * double(std::max(scene.scene_radius(), 1e-3f)));
}


}  // namespace dp::integrators
