#include "apps/output.h"

#include <sys/resource.h>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/log.h"

namespace dp::apps {

std::string sibling_path(const std::string& exr_path, const std::string& ext) {
  const size_t dot = exr_path.rfind('.');
  const size_t slash = exr_path.find_last_of('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? exr_path.substr(0, dot) : exr_path) + ext;
}

namespace {
// Peak resident set size of this process so far, in bytes (Linux reports KiB); 0 if unknown.
uint64_t peak_rss_bytes() {
  rusage ru{};
  if (getrusage(RUSAGE_SELF, &ru) != 0 || ru.ru_maxrss <= 0) return 0;
  return uint64_t(ru.ru_maxrss) * 1024u;
}
}  // namespace

void write_render_outputs(const std::string& exr_path, integrators::RenderResult& result, core::Json sidecar) {
  size_t nonfinite = 0;
  for (auto& l : result.layers) nonfinite += l.image.zero_nonfinite();
  if (nonfinite > 0) log::warn(nonfinite, " non-finite pixels were zeroed before writing (this is a bug; please report)");
  core::write_exr(exr_path, result.layers);
  core::write_png(sibling_path(exr_path, ".png"), result.layers.at(0).image);

  if (result.min_spp == 0 && !result.partial) {  // e.g. a time budget below one pass
    log::warn("some pixels have no sample (time budget too small?): the output is marked partial");
    result.partial = true;
  }
  sidecar["nonfinite_pixels_zeroed"] = uint64_t(nonfinite);
  write_sidecar(exr_path, result, std::move(sidecar));
}

void write_sidecar(const std::string& exr_path, const integrators::RenderResult& result, core::Json sidecar) {
  sidecar["wall_seconds"] = result.wall_seconds;
  sidecar["spp_min"] = result.min_spp;
  sidecar["spp_max"] = result.max_spp;
  sidecar["partial"] = result.partial;
  sidecar["peak_rss_bytes"] = peak_rss_bytes();  // the whole process: scene, render and outputs
  if (!result.layers.empty()) {
    core::Json layers = core::Json::array();
    for (const auto& l : result.layers) layers.push_back(l.name.empty() ? "RGB" : l.name);
    sidecar["layers"] = layers;
    const Rgbd mean = result.layers.at(0).image.mean();
    sidecar["mean"] = core::Json(core::Json::Array{mean[0], mean[1], mean[2]});
  }
  core::Json counters = core::Json::object();
  for (const auto& [k, v] : result.stats.counters()) counters[k] = v;
  sidecar["counters"] = counters;
  sidecar["info"] = result.info;
  core::write_file_atomically(sibling_path(exr_path, ".json"), sidecar.dump());
}

}  // namespace dp::apps
