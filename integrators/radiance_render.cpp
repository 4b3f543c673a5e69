#include "integrators/radiance_render.h"

#include <algorithm>

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
  auto& count = raw.counts["spp"];
  count.resize(raw.pixels());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) count[size_t(y) * size_t(w) + size_t(x)] = sched.spp_at(x, y);
  // The image goes through finish() as a merge of --partial files does: same code, same bits.
  RenderOptions target = options;
  if (options.time_budget > 0) target.spp = 0;  // a time budget has no spp to fall short of
  RenderResult result = options.raw ? RenderResult{} : finish_radiance(raw, target);
  const bool has_spp_layer = !result.layers.empty() && result.layers.back().name == "spp";
  if (sched.partial && !options.raw && !has_spp_layer) result.layers.push_back({"spp", sched.spp_image()});
  if (options.raw) result.raw = std::move(raw);
  for (const auto& s : thread_stats) result.stats.merge(s);
  result.wall_seconds = sched.seconds;
  result.min_spp = sched.min_spp();
  result.max_spp = sched.max_spp();
  result.partial = sched.partial;
  result.info["passes"] = sched.passes;
  return result;
}

RenderResult finish_radiance(const core::RawImage& raw, const RenderOptions& options) {
  const std::vector<Rgbd>& sum = raw.sum("radiance");
  const std::vector<int64_t>& count = raw.count("spp");
  RenderResult result;
  core::Image img(raw.width, raw.height), spp(raw.width, raw.height);
  result.min_spp = count.empty() ? 0 : count[0];
  result.max_spp = result.min_spp;
  for (size_t i = 0; i < count.size(); ++i) {
    const int64_t n = count[i];
    if (n > 0) img[i] = (sum[i] / double(n)).cast<float>();
    spp[i] = Rgb::Constant(float(n));
    result.min_spp = std::min(result.min_spp, n);
    result.max_spp = std::max(result.max_spp, n);
  }
  result.partial = result.min_spp < options.spp;
  result.layers.push_back({"", std::move(img)});
  // Which pixels lack samples (as ScheduleResult::fill): their counts.
  if (result.partial || result.min_spp != result.max_spp) result.layers.push_back({"spp", std::move(spp)});
  return result;
}

}  // namespace dp::integrators
