// `deltapath experiment FILE [--out DIR] [--threads T] [--no-plot] [--quiet]`: renders
// every (run, budget, seed) point of an experiment file, skipping finished points, and
// writes results.csv, the convergence plot and report.html into the output folder.
// SIGINT/SIGTERM stop at the next tile boundary; the interrupted point is not kept (the
// finished ones are, and a re-run resumes) and deltapath exits 128 + signal.
#include "apps/cmd_experiment.h"

#include <cstdio>
#include <filesystem>

#include "apps/cli_checks.h"
#include "apps/interrupt.h"
#include "core/log.h"
#include "experiments/config.h"
#include "experiments/runner.h"

namespace dp::apps {

namespace {
struct ExperimentArgs {
  std::string file, out;
  int threads = 0;
  bool no_plot = false, quiet = false;
};

void run(const ExperimentArgs& a) {
  if (a.quiet) log::set_level(log::Level::warn);
  set_early_exit_message("interrupted while loading the experiment; nothing written");
  experiments::ExperimentConfig config = experiments::parse_experiment(a.file);
  if (!a.out.empty()) config.output = std::filesystem::path(a.out).lexically_normal().string();
  experiments::RunnerOptions opt;
  opt.render.threads = a.threads;
  opt.render.quiet = a.quiet;
  opt.render.stop = stop_flag();
  opt.scene_loaded = enable_graceful_stop;
  opt.plot = !a.no_plot;
  const experiments::ExperimentResult r = experiments::run_experiment(config, opt);
  std::printf("experiment %s: %zu points rendered, %zu already done\n", config.name.c_str(), r.rendered, r.skipped);
  std::printf("  csv:    %s\n", r.csv_path.c_str());
  std::printf("  plot:   %s\n", r.plot_png.empty() ? "(none)" : r.plot_png.c_str());
  std::printf("  report: %s\n", r.report_path.c_str());
}
}  // namespace

void register_experiment(CLI::App& app) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* cmd = app.add_subcommand("experiment", "run an experiment file: renders, CSV, convergence plot, HTML report");
  cmd->add_option("file", args->file, "experiment file (YAML)")->required();
  cmd->add_option("--out", args->out, "output folder (default: the file's `output`)");
  cmd->add_option("--threads", args->threads, "worker threads per render (default: all cores)")->check(thread_count());
  cmd->add_flag("--no-plot", args->no_plot, "do not run the plot script");
  cmd->add_flag("--quiet", args->quiet, "no progress lines or info messages");
  cmd->callback([args] { run(*args); });
}

}  // namespace dp::apps
