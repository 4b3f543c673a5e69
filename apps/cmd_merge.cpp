// `deltapath merge A.exr B.exr ... --out C.exr` (issue 17): sums the raw buffers and
// sample counts of `render --partial` files (apps/partial_file.h) that are parts of one
// render, then writes the outputs `render` would have written (C.exr with every layer,
// C.png, C.json), the gradient integrators' Poisson reconstruction included. Files that
// are not parts of the same render (integrator, settings, seed, spp, scene hash, size,
// version, part count) or repeat a part are refused with one line naming the difference.
// Missing parts are allowed with a warning: the image has fewer samples, marked partial.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <set>

#include "apps/cli_checks.h"
#include "apps/commands.h"
#include "apps/output.h"
#include "apps/partial_file.h"
#include "core/error.h"
#include "core/log.h"
#include "core/timer.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"

namespace dp::apps {

namespace {
struct MergeArgs {
  std::vector<std::string> inputs;
  std::string out = "merged.exr";
  int threads = 0;
  bool quiet = false;
};

// Reads every input's header and checks that they are distinct parts of one render;
// returns them sorted by part, so the sum does not depend on the order of the command line.
std::vector<PartialFile> read_parts(const std::vector<std::string>& paths) {
  std::vector<PartialFile> files;
  for (const auto& p : paths) {
    files.push_back(read_partial(p, false));
    const PartialFile& f = files.back();
    const PartialFile& first = files.front();
    const std::string diff = first_difference(first, f);
    if (!diff.empty()) throw ValueError("cannot merge with " + first.path + ": " + diff, f.path);
    for (size_t i = 0; i + 1 < files.size(); ++i)
      if (files[i].part == f.part)
        throw ValueError("part " + std::to_string(f.part) + "/" + std::to_string(f.parts) + " is also in " +
                             files[i].path + " (merge each part once)",
                         f.path);
  }
  std::sort(files.begin(), files.end(), [](const PartialFile& a, const PartialFile& b) { return a.part < b.part; });
  return files;
}

int64_t fact_int(const PartialFile& f, const std::string& key) { return integer_fact(f, key, INT64_MIN, INT64_MAX); }

void run_merge(const MergeArgs& a) {
  if (a.quiet) log::set_level(log::Level::warn);
  core::Timer timer;
  const std::vector<PartialFile> files = read_parts(a.inputs);
  const PartialFile& first = files.front();
  // One file's pixels in memory at a time besides the total, added in part order.
  core::RawImage total = read_partial(first.path).raw;
  for (size_t i = 1; i < files.size(); ++i) {
    const PartialFile part = read_partial(files[i].path);
    const std::string diff = total.layout_difference(part.raw);
    if (!diff.empty()) throw ValueError("cannot merge with " + first.path + ": buffers differ: " + diff, part.path);
    total.add(part.raw);
  }

  integrators::Settings settings;
  for (const auto& [k, v] : first.facts)
    if (k.rfind("setting.", 0) == 0) settings.set(k.substr(8), v, first.path);
  const std::string name = first.facts.at("integrator");
  auto integrator = integrators::make_integrator(name, settings);
  if (!integrator->supports_raw())
    throw ValueError("integrator " + name + " does not support --partial yet", first.path);

  integrators::RenderOptions opt;
  opt.spp = int(fact_int(first, "spp"));
  opt.max_depth = int(fact_int(first, "max_depth"));
  opt.seed = uint64_t(fact_int(first, "seed"));
  opt.threads = a.threads;
  opt.quiet = a.quiet;
  integrators::RenderResult result;
  try {
    result = integrator->finish(total, opt);
  } catch (const ValueError& e) {  // e.g. a buffer this integrator needs is not in the files
    throw ValueError(e.message(), first.path);
  }

  // Which parts are here, which are missing, which were interrupted.
  core::Json merged = core::Json::array(), from = core::Json::array();
  std::set<int> present;
  bool interrupted = false;
  int64_t passes = 0;
  double part_seconds = 0;
  for (const PartialFile& f : files) {
    present.insert(f.part);
    merged.push_back(f.part);
    from.push_back(f.path);
    interrupted |= f.facts.at("interrupted") == "true";
    passes = std::max(passes, fact_int(f, "passes"));  // passes any part took part in
    part_seconds += std::strtod(f.facts.at("wall_seconds").c_str(), nullptr);
    for (const auto& [k, v] : f.facts)
      if (k.rfind("counter.", 0) == 0) result.stats.add(k.substr(8), fact_int(f, k));
  }
  if (int(present.size()) < first.parts) {
    std::string missing;
    for (int k = 1; k <= first.parts; ++k)
      if (!present.count(k)) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    log::warn("parts ", missing, " of ", first.parts,
              " are missing: the merged image has fewer samples (marked partial)");
    result.partial = true;
  }
  if (interrupted) {
    log::warn("some parts were interrupted: the merged image is marked partial");
    result.partial = true;
  }
  result.info["passes"] = passes;

  core::Json side = core::Json::object();
  side["scene"] = first.facts.at("scene");
  side["scene_hash"] = first.facts.at("scene_hash");
  side["integrator"] = name;
  side["settings"] = settings.to_json();
  side["seed"] = fact_int(first, "seed");
  side["threads"] = integrators::resolve_threads(opt);
  side["max_depth"] = opt.max_depth;
  side["spp_requested"] = opt.spp > 0 ? core::Json(opt.spp) : core::Json(nullptr);  // null: --time parts
  side["parts"] = first.parts;
  side["parts_merged"] = merged;
  side["merged_from"] = from;
  side["parts_wall_seconds"] = part_seconds;  // summed over the parts (render time, not merge time)
  side["merge_seconds"] = timer.seconds();
  write_render_outputs(a.out, result, side);
  log::info("merged ", files.size(), " of ", first.parts, " parts into ", a.out, " (", result.min_spp, " spp)");
}
}  // namespace

void register_merge(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "sum `render --partial` files and write the render's outputs");
  cmd->add_option("inputs", args->inputs, "partial EXR files (parts of one render)")->required();
  cmd->add_option("--out", args->out, "output EXR (also writes .png and .json beside it)");
  cmd->add_option("--threads", args->threads, "threads of the reconstruction (default: all cores)")
      ->check(thread_count());
  cmd->add_flag("--quiet", args->quiet, "no info messages");
  cmd->callback([args] { run_merge(*args); });
}

}  // namespace dp::apps
