#include "mcmc/path_seed.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/thread_pool.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::mcmc {

using pathspace::BidirVertex;

namespace {

core::Rng sample_rng(uint64_t seed, int64_t i) { return core::Rng(seed, core::mix64(0x5EED'0000'0000ull + uint64_t(i))); }

struct Subpaths {
  std::vector<BidirVertex> light, camera;
};

// BDPT sample i (as the `bdpt` integrator's, with the raster uniform on the whole image);
// calls visit(s, t, lum(w C)) for every strategy with a non-zero value.
template <class Visit>
void bdpt_sample(const scene::Scene& scene, const PathSeedOptions& opt, int64_t i, Subpaths& sp, Visit&& visit) {
  core::Rng rng = sample_rng(opt.seed, i);
  const scene::PerspectiveCamera& cam = scene.camera();
  const Vec2 u = rng.uniform2();
  const Vec2 raster(std::min(u.x() * float(cam.width()), std::nextafter(float(cam.width()), 0.0f)),
                    std::min(u.y() * float(cam.height()), std::nextafter(float(cam.height()), 0.0f)));
  pathspace::SubpathParams cp, lp;
  cp.max_vertices = opt.max_depth + 1;
  lp.max_vertices = opt.max_depth;
  cp.rr_depth = lp.rr_depth = opt.rr_depth;
  pathspace::camera_subpath(scene, raster, cp, rng, sp.camera);
  pathspace::light_subpath(scene, lp, rng, sp.light);
  const pathspace::MisConfig mis;  // power heuristic
  const int nl = int(sp.light.size()), nc = int(sp.camera.size());
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= nl; ++s) {
      if (s + t < 2 || s + t - 1 > opt.max_depth || s + t - 1 < opt.min_depth) continue;
      pathspace::Connection c;
      if (!pathspace::connect(scene, sp.light.data(), s, sp.camera.data(), t, mis, c)) continue;
      visit(s, t, double(luminance(c.value)) * double(c.weight), c.value);
    }
}

}  // namespace

PathSeeder::PathSeeder(const scene::Scene& scene, const PathSeedOptions& options) : m_scene(scene), m_opt(options) {
  const int64_t n = std::max<int64_t>(options.samples, 0);
  m_sum.assign(size_t(n), 0.0);
  m_bad.assign(size_t(n), 0);
  std::atomic<int64_t> invalid{0};
  core::parallel_for((n + kBlock - 1) / kBlock, options.threads, [&](int64_t block, int) {
    Subpaths sp;
    for (int64_t i = block * kBlock; i < std::min(n, (block + 1) * kBlock); ++i) {
      double sum = 0.0;
      bool finite = true;
      bdpt_sample(m_scene, m_opt, i, sp, [&](int, int, double w, const Rgb& value) {
        if (!std::isfinite(w) || !is_finite(value)) finite = false;
        else sum += std::max(0.0, w);
      });
      if (!finite) {
        invalid.fetch_add(1);
        m_bad[size_t(i)] = 1;
        sum = 0.0;
      }
      m_sum[size_t(i)] = sum;
    }
  });
  m_invalid = invalid.load();
  m_cdf.resize(m_sum.size());
  double total = 0.0;
  for (size_t i = 0; i < m_sum.size(); ++i) m_cdf[i] = total += m_sum[i];  // index order: deterministic
  m_b = n > 0 ? total / double(n) : 0.0;
}

SampleShare PathSeeder::share(int part, int parts) const {
  SampleShare s;
  for (size_t i = 0; i < m_sum.size(); ++i)
    if (owns_sample(int64_t(i), kBlock, part, parts)) {
      s.sum += m_sum[i];
      ++s.n;
      s.invalid += m_bad[i];
    }
  return s;
}

bool PathSeeder::select(double u, PathState& out, PathSides& sides) const {
  if (m_cdf.empty() || !(m_cdf.back() > 0.0)) return false;
  const double target = u * m_cdf.back();
  auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), target);
  if (it == m_cdf.end()) --it;
  int64_t i = int64_t(it - m_cdf.begin());
  while (i > 0 && !(m_sum[size_t(i)] > 0.0)) --i;
  // The residual of u picks the strategy within the sample.
  const double before = m_cdf[size_t(i)] - m_sum[size_t(i)];
  double rest = std::clamp(target - before, 0.0, m_sum[size_t(i)]);
  Subpaths sp;
  int pick_s = -1, pick_t = -1, last_s = -1, last_t = -1;
  bdpt_sample(m_scene, m_opt, i, sp, [&](int s, int t, double w, const Rgb&) {
    if (!(w > 0.0)) return;
    last_s = s, last_t = t;
    if (pick_s < 0 && rest < w) pick_s = s, pick_t = t;
    rest -= w;
  });
  if (pick_s < 0) pick_s = last_s, pick_t = last_t;  // round-off at the sample's end
  if (pick_t < 1) return false;
  path_of_strategy(sp.light.data(), pick_s, sp.camera.data(), pick_t, out.v);
  return evaluate_path(m_scene, out, sides);
}

}  // namespace dp::mcmc
