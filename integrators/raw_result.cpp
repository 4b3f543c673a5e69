#include "integrators/raw_result.h"

#include <algorithm>

namespace dp::integrators {

std::vector<int64_t> spp_counts(const ScheduleResult& sched, int width, int height) {
  std::vector<int64_t> count(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) count[size_t(y) * size_t(width) + size_t(x)] = sched.spp_at(x, y);
  return count;
}

void fill_counts(const std::vector<int64_t>& count, int width, int height, const RenderOptions& options,
                 RenderResult& result) {
  core::Image spp(width, height);
  result.min_spp = count.empty() ? 0 : count[0];
  result.max_spp = result.min_spp;
  for (size_t i = 0; i < count.size(); ++i) {
    spp[i] = Rgb::Constant(float(count[i]));
    result.min_spp = std::min(result.min_spp, count[i]);
    result.max_spp = std::max(result.max_spp, count[i]);
  }
  result.partial = result.min_spp < options.spp;
  if (result.partial || result.min_spp != result.max_spp) result.layers.push_back({"spp", std::move(spp)});
}

RenderResult finish_tiled(const FinishFunction& finish, core::RawImage raw, const ScheduleResult& sched,
                          const RenderOptions& options) {
  RenderOptions target = options;
  if (options.time_budget > 0) target.spp = 0;  // a time budget has no spp to fall short of
  RenderResult result = options.raw ? RenderResult{} : finish(raw, target);
  const bool has_spp_layer = !result.layers.empty() && result.layers.back().name == "spp";
  if (sched.partial && !options.raw && !has_spp_layer) result.layers.push_back({"spp", sched.spp_image()});
  if (options.raw) result.raw = std::move(raw);
  result.wall_seconds = sched.seconds;
  result.min_spp = sched.min_spp();
  result.max_spp = sched.max_spp();
  result.partial = sched.partial;
  result.info["passes"] = sched.passes;
  return result;
}

RenderResult finish_iterations(const FinishFunction& finish, int width, int height, std::vector<Rgbd>&& total,
                               int64_t done, int64_t target, bool stopped, const RenderOptions& options) {
  core::RawImage raw;
  raw.width = width;
  raw.height = height;
  raw.sums["radiance"] = std::move(total);
  raw.counts["spp"].assign(size_t(width) * size_t(height), done);  // one sample per pixel per iteration
  const bool timed = options.time_budget > 0;
  RenderOptions finish_options = options;
  if (timed) finish_options.spp = 0;  // a time budget has no count to fall short of
  RenderResult result = options.raw ? RenderResult{} : finish(raw, finish_options);
  if (options.raw) result.raw = std::move(raw);
  result.min_spp = result.max_spp = done;
  result.partial = stopped || (!timed && done < target);  // a stop, also in --time mode
  return result;
}

}  // namespace dp::integrators
