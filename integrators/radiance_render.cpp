#include "integrators/radiance_render.h"

#include <algorithm>

#include "integrators/raw_result.h"

namespace dp::integrators {

namespace {

RenderResult render(const scene::Scene& scene, const RenderOptions& options, const std::string& label,
                    const RadianceSplatTileFunction& fn, bool splats) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  std::vector<Rgbd> sum(size_t(w) * size_t(h), Rgbd::Zero()), light;
  if (splats) light.assign(sum.size(), Rgbd::Zero());
  std::vector<core::Stats> thread_stats(size_t(resolve_threads(options)));
  const int tiles = ((w + kTileSize - 1) / kTileSize) * ((h + kTileSize - 1) / kTileSize);
  SplatMerger merger(splats ? size_t(tiles) : 0, light);

  const ScheduleResult sched = run_tiles(
      w, h, options, label,
      [&](const Tile& tile, int spp, core::Rng& rng, int thread) {
        std::vector<Splat> list;
        fn(tile, spp, rng, sum, list, thread_stats[size_t(thread)]);
        if (splats) merger.submit(tile.index, std::move(list));
      },
      [&](int64_t, bool) {
        if (splats) merger.finish_pass();
      });

  core::RawImage raw;
  raw.width = w;
  raw.height = h;
  raw.sums["radiance"] = std::move(sum);
  if (splats) raw.sums["light"] = std::move(light);
  raw.counts["spp"] = spp_counts(sched, w, h);
  // The image goes through finish() as a merge of --partial files does: same code, same bits.
  RenderResult result = finish_tiled(finish_radiance, std::move(raw), sched, options);
  for (const auto& s : thread_stats) result.stats.merge(s);
  return result;
}

}  // namespace

RenderResult render_radiance(const scene::Scene& scene, const RenderOptions& options, const std::string& label,
                             const RadianceTileFunction& fn) {
  return render(scene, options, label,
                [&](const Tile& tile, int spp, core::Rng& rng, std::vector<Rgbd>& sum, std::vector<Splat>&,
                    core::Stats& stats) { fn(tile, spp, rng, sum, stats); },
                false);
}

RenderResult render_radiance_with_splats(const scene::Scene& scene, const RenderOptions& options,
                                         const std::string& label, const RadianceSplatTileFunction& fn) {
  return render(scene, options, label, fn, true);
}

RenderResult finish_radiance(const core::RawImage& raw, const RenderOptions& options) {
  const std::vector<Rgbd>& sum = raw.sum("radiance");
  const std::vector<int64_t>& count = raw.count("spp");
  RenderResult result;
  core::Image img(raw.width, raw.height);
  for (size_t i = 0; i < count.size(); ++i)
    if (count[i] > 0) img[i] = (sum[i] / double(count[i])).cast<float>();
  if (raw.sums.count("light") != 0) {  // light tracing: one light path per camera sample
    const std::vector<Rgbd>& light = raw.sum("light");
    double light_paths = 0;
    for (const int64_t n : count) light_paths += double(n);
    const double scale = light_paths > 0 ? double(raw.pixels()) / light_paths : 0.0;
    for (size_t i = 0; i < count.size(); ++i) img[i] += (light[i] * scale).cast<float>();
    result.info["light_paths"] = light_paths;
  }
  result.layers.push_back({"", std::move(img)});
  fill_counts(count, raw.width, raw.height, options, result);
  return result;
}

}  // namespace dp::integrators
