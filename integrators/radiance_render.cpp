#include "integrators/radiance_render.h"

#include <algorithm>

#include "integrators/raw_result.h"

namespace dp::integrators {

RenderResult render_radiance(const scene::Scene& scene, const RenderOptions& options, const std::string& label,
                             const RadianceTileFunction& fn) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero());
  std::vector<core::Stats> thread_stats(size_t(resolve_threads(options)));

  const ScheduleResult sched = run_tiles(w, h, options, label, [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
    fn(tile, spp, rng, sum, thread_stats[size_t(thread)]);
  });

  core::RawImage raw;
  raw.width = w;
  raw.height = h;
  raw.sums["radiance"] = std::move(sum);
  raw.counts["spp"] = spp_counts(sched, w, h);
  // The image goes through finish() as a merge of --partial files does: same code, same bits.
  RenderResult result = finish_tiled(finish_radiance, std::move(raw), sched, options);
  for (const auto& s : thread_stats) result.stats.merge(s);
  return result;
}

RenderResult finish_radiance(const core::RawImage& raw, const RenderOptions& options) {
  const std::vector<Rgbd>& sum = raw.sum("radiance");
  const std::vector<int64_t>& count = raw.count("spp");
  RenderResult result;
  core::Image img(raw.width, raw.height);
  for (size_t i = 0; i < count.size(); ++i)
    if (count[i] > 0) img[i] = (sum[i] / double(count[i])).cast<float>();
  result.layers.push_back({"", std::move(img)});
  fill_counts(count, raw.width, raw.height, options, result);
  return result;
}

}  // namespace dp::integrators
