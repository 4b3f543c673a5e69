#include "integrators/direct_pass.h"

#include <algorithm>
#include <atomic>

#include "integrators/tile_scheduler.h"

namespace dp::integrators {

DirectPass::DirectPass(const scene::Scene& scene, const PathSettings& settings, const RenderOptions& options,
                       std::string label)
    : m_scene(scene),
      m_tracer(scene, settings, std::min(2, options.max_depth)),
      m_opt(options),
      m_label(std::move(label)),
      m_w(scene.camera().width()),
      m_h(scene.camera().height()),
      m_sum(size_t(m_w) * size_t(m_h), Rgbd::Zero()),
      m_count(size_t(m_w) * size_t(m_h), 0) {
  m_opt.time_budget = 0;
  m_opt.quiet = true;
}

void DirectPass::render(int spp) {
  if (spp <= 0) return;
  RenderOptions o = m_opt;
  o.spp = spp;
  // Mixed before the pass index is added: seed ^ (c + pass) would give run s's pass p+1 the
  // stream of run s^1's pass p (independent renders sharing samples: caught by test_gdmlt).
  o.seed = core::mix64(core::mix64(m_opt.seed ^ 0xD1EC'7000'0000'0001ull) + uint64_t(m_passes++));
  std::atomic<int64_t> dropped{0};
  const auto& cam = m_scene.camera();
  const ScheduleResult sched = run_tiles(m_w, m_h, o, m_label, [&](const Tile& tile, int n, core::Rng& rng, int) {
    PathCounters counters;
    int64_t bad = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        for (int i = 0; i < n; ++i) {
          const Vec2 raster(float(x) + rng.uniform(), float(y) + rng.uniform());
          const Rgb L = m_tracer.radiance(cam.generate_ray(raster), rng, counters);
          if (is_finite(L)) m_sum[size_t(y) * size_t(m_w) + size_t(x)] += L.cast<double>();
          else ++bad;  // counted and dropped, never splatted
        }
    dropped.fetch_add(bad);
  });
  for (int y = 0; y < m_h; ++y)
    for (int x = 0; x < m_w; ++x) m_count[size_t(y) * size_t(m_w) + size_t(x)] += sched.spp_at(x, y);
  m_dropped += dropped.load();
  m_spp += spp;
  m_partial |= sched.partial;
}

namespace {
core::Image mean_image(const std::vector<Rgbd>& sum, const std::vector<int64_t>& count, int w, int h) {
  core::Image img(w, h);
  for (size_t i = 0; i < sum.size(); ++i)
    if (count[i] > 0) img[i] = (sum[i] / double(count[i])).cast<float>();
  return img;
}
}  // namespace

void DirectPass::catch_up(int64_t spp) {
  while (m_spp < spp) render(1);
}

core::Image DirectPass::image() const { return mean_image(m_sum, m_count, m_w, m_h); }

void DirectPass::write(core::RawImage& raw) const {
  raw.sums["direct"] = m_sum;
  raw.counts["direct"] = m_count;
}

core::Image DirectPass::image(const core::RawImage& raw) {
  return mean_image(raw.sum("direct"), raw.count("direct"), raw.width, raw.height);
}

}  // namespace dp::integrators
