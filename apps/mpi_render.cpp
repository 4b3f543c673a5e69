#include "apps/mpi_render.h"

#include <cmath>
#include <cstdlib>

#include "apps/output.h"
#include "core/error.h"
#include "core/log.h"
#include "core/raw_bytes.h"
#include "core/timer.h"

namespace dp::apps {

void mpi_reduce_and_write(const MpiWorld& world, const integrators::Integrator& integrator,
                          const integrators::RenderOptions& options, const integrators::RenderResult& result,
                          core::Json side, const std::string& out) {
  std::map<std::string, std::string> facts;
  facts["wall_seconds"] = std::to_string(result.wall_seconds);
  facts["interrupted"] = result.partial ? "true" : "false";
  core::Json info = result.info;
  const double passes = info["passes"].number();
  facts["passes"] = std::to_string(std::isfinite(passes) ? int64_t(passes) : int64_t(0));
  for (const auto& [k, v] : result.stats.counters()) facts["counter." + k] = std::to_string(v);
  core::Timer timer;
  core::RawImage total;
  core::Json rank_seconds = core::Json::array();
  bool interrupted = false;
  int64_t max_passes = 0, bytes = 0;
  core::Stats counters;
  // Rank 0 adds each rank's buffers as they arrive, in rank order (deterministic sums).
  mpi_gather_each(core::raw_to_bytes(result.raw, facts), [&](int r, const std::vector<uint8_t>& b) {
    std::map<std::string, std::string> f;
    core::RawImage raw = core::raw_from_bytes(b, f);
    if (r == 0) {
      total = std::move(raw);
    } else {
      const std::string diff = total.layout_difference(raw);
      if (!diff.empty()) throw Error("rank " + std::to_string(r) + "'s buffers differ from rank 0's: " + diff);
      total.add(raw);
      bytes += int64_t(b.size());
    }
    rank_seconds.push_back(std::strtod(f["wall_seconds"].c_str(), nullptr));
    interrupted |= f["interrupted"] == "true";
    max_passes = std::max<int64_t>(max_passes, std::strtoll(f["passes"].c_str(), nullptr, 10));
    for (const auto& [k, v] : f)
      if (k.rfind("counter.", 0) == 0) counters.add(k.substr(8), std::strtoll(v.c_str(), nullptr, 10));
  });
  if (world.rank != 0) return;
  const double gather_seconds = timer.seconds();
  integrators::RenderOptions finish_options = options;
  if (options.time_budget > 0) finish_options.spp = 0;  // a timed render: no count to reach (as merge)
  integrators::RenderResult merged = integrator.finish(total, finish_options);
  for (const auto& [k, v] : counters.counters()) merged.stats.add(k, v);
  if (interrupted) {
    log::warn("some ranks were interrupted: the image is marked partial");
    merged.partial = true;
  }
  merged.info["passes"] = max_passes;
  side["ranks"] = world.size;
  side["rank_wall_seconds"] = rank_seconds;
  side["mpi_bytes_gathered"] = bytes;  // buffers sent to rank 0 by the other ranks
  side["mpi_gather_seconds"] = gather_seconds;
  side["mpi_finish_seconds"] = timer.seconds() - gather_seconds;
  write_render_outputs(out, merged, side);
  log::info("wrote ", out, " (", world.size, " ranks, ", merged.min_spp, " spp)");
}

}  // namespace dp::apps
