// The experiment runner: renders every (run, budget, seed) point, scores it against
// the reference, and writes into the output folder
//   runs/<run>/<budget>-seed<k>.exr|.png|.json   each point's layers, preview, sidecar
//   runs/<run>/<budget>-seed<k>.done              written last: the point is finished
//   results.csv                                   name,budget,seed,wall_time,spp,<metrics>
//   convergence.png|.svg                          plot_convergence.py (if python3 works)
//   report.html + report/                         the HTML report (report.h)
// Resumable: a point whose .done marker exists and whose key (scene bytes, integrator,
// resolved settings, budget, seed, max_depth) matches is not rendered again; its
// metrics are recomputed from its EXR (so adding a metric needs no re-render).
// wall_time is measured around Integrator::render on steady_clock. Points run seed by
// seed, budget by budget, so an interrupted experiment has whole early seeds.
// The reference cache (reference.h) is <output>/../reference-cache, shared by the
// experiments writing into the same parent folder.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "experiments/config.h"
#include "experiments/reference.h"

namespace dp::experiments {

struct RunnerOptions {
  RenderContext render;
  bool plot = true;    // run plot_convergence.py
  bool report = true;  // write report.html
  bool progress = true;  // one progress line per point on stderr
  // Called once the scene is loaded (the CLI switches SIGINT/SIGTERM from "exit now" to
  // "stop the render", apps/interrupt.h). May be empty.
  std::function<void()> scene_loaded;
};

struct PointResult {
  size_t run = 0, budget = 0;
  int seed = 0;
  double wall_time = 0;
  int64_t spp = 0;
  std::vector<double> metrics;  // in config.metrics order
  std::string exr_path;         // all layers of the render
  std::string layer;            // the scored layer's name ("" = main)
  bool skipped = false;         // finished by an earlier invocation
};

struct ExperimentResult {
  std::string output_dir, csv_path, report_path;
  std::string plot_png;  // empty when no plot was made
  std::string reference_path;
  std::vector<PointResult> points;  // sorted by run, budget, seed
  size_t rendered = 0, skipped = 0;
};

ExperimentResult run_experiment(const ExperimentConfig& config, const RunnerOptions& options);

// "<output>/runs/<slug>/<budget label>-seed<k>" (add .exr/.png/.json/.done).
std::string point_stem(const ExperimentConfig& config, size_t run, size_t budget, int seed);
// Human-readable duration: "1.25s", "45s", "3m20s", "1h02m".
std::string format_duration(double seconds);

}  // namespace dp::experiments
