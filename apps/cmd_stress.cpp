// `deltapath stress [--quick] [--seed S] [--integrator NAME ...] [--variants N]
// [--threads T] [--csv FILE] [--images DIR]`: renders the randomized stress scenes with every
// integrator, prints NaN/Inf drops, failure counters and maximum pixel values, and
// exits non-zero if a non-finite value reached any image buffer.
#include "apps/cmd_stress.h"

#include <cstdio>

#include "apps/cli_checks.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "experiments/stress.h"

namespace dp::apps {

namespace {
struct StressArgs {
  experiments::StressOptions options;
  std::string csv;
};

void run(const StressArgs& a) {
  const experiments::StressReport report = experiments::run_stress(a.options);
  std::printf("%s", experiments::format_stress_report(report).c_str());
  if (!a.csv.empty()) core::write_file_atomically(a.csv, experiments::stress_csv(report));
  if (report.nonfinite_pixels() > 0)
    throw Error("stress: " + std::to_string(report.nonfinite_pixels()) + " non-finite pixel values reached image buffers");
  std::printf("stress: OK, no non-finite value reached an image buffer\n");
}
}  // namespace

void register_stress(CLI::App& app) {
  auto args = std::make_shared<StressArgs>();
  CLI::App* cmd = app.add_subcommand("stress", "numerical stability run over randomized hard scenes, every integrator");
  cmd->add_flag("--quick", args->options.quick, "CI version: two small variants per scene family, fewer beam/plane light paths");
  cmd->add_option("--seed", args->options.seed, "randomization seed (default 1)");
  cmd->add_option("--integrator", args->options.integrators, "only these integrators (repeatable; default all)");
  cmd->add_option("--variants", args->options.variants, "random variants per scene family (default 2 quick, 4 full)");
  cmd->add_option("--threads", args->options.threads, "worker threads (default: all cores)")->check(thread_count());
  cmd->add_option("--csv", args->csv, "also write the table as CSV");
  cmd->add_option("--images", args->options.image_dir, "write a PNG preview of every render into this folder");
  cmd->callback([args] { run(*args); });
}

}  // namespace dp::apps
