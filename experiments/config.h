// Experiment files (YAML). Schema (issue 7); paths are relative to the file:
//
//   name: cbox-gpt-vs-pt                 # required; used in the report title
//   scene: ../scenes/cornell.yaml        # required; YAML or Mitsuba XML
//   reference: {file: ref.exr}           # or {integrator: path, spp: 65536}: rendered
//                                        #   once and cached (see reference.h)
//   budget: {time: [5, 10, 20]}          # wall seconds per render; or {spp: [16, 64]}
//   seeds: 3                             # independent repetitions per point (default 1)
//   runs:                                # required, at least one
//     - {name: PT, integrator: path}
//     - {name: G-PT L1, integrator: gpt, reconstruction: l1}
//     - {name: G-PT L2, integrator: gpt, reconstruction: l2, settings: {alpha: 0.2}}
//   metrics: [relmse, mse]               # relmse | mse | mape, or {metric: relmse,
//                                        #   discard: N} to drop the N worst pixels
//   crops: [[x, y, w, h], ...]           # optional insets for the report (pixels)
//   output: results/cbox-gpt-vs-pt       # default: results/<name>
//   launcher: mpirun -np 4               # optional: every point runs as `<launcher>
//                                        #   deltapath render ...` (launcher.h)
//
// A run's `reconstruction` and `settings` become integrator settings (`--set
// reconstruction=l2`, `--set alpha=0.2`); the integrator rejects keys it does not know.
// The scored layer follows `reconstruction` (see scoring.h). Unknown keys anywhere are
// dp::ParseError with file:line; out-of-range values dp::ValueError with file:line.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dp::experiments {

enum class BudgetKind { time, spp };

struct Metric {
  std::string name;  // relmse | mse | mape
  size_t discard = 0;
  int crop = -1;  // index into Config::crops: scored on that region only; -1: whole image
  // CSV column: "relmse", "relmse_discard10" when pixels are discarded, "relmse_crop0"
  // on crop 0 (both suffixes may combine).
  std::string column() const;
};

struct Crop {
  int x = 0, y = 0, w = 0, h = 0;
  int line = 0;  // in the experiment file (checked against the image size later)
};

struct Run {
  std::string name;
  std::string slug;  // file-name form of `name` (unique within the experiment)
  std::string integrator;
  std::string reconstruction;  // "" = not given
  std::vector<std::pair<std::string, std::string>> settings;  // verbatim scalar values
  int line = 0;
};

struct ReferenceSpec {
  std::string file;        // set for {file: ...} (resolved path)
  std::string integrator;  // set for {integrator: ..., spp: ...}
  int64_t spp = 0;
  int line = 0;
};

struct ExperimentConfig {
  std::string file;  // the experiment file as given
  std::string name;
  std::string scene;  // resolved path
  ReferenceSpec reference;
  BudgetKind budget_kind = BudgetKind::spp;
  std::vector<double> budgets;  // seconds or spp, in file order
  int seeds = 1;
  std::vector<Run> runs;
  std::vector<Metric> metrics;  // default: relmse
  std::vector<Crop> crops;
  std::string output;  // resolved path
  std::vector<std::string> launcher;  // command prefix, split at whitespace; empty: in process

  // "5 s" / "16 spp" for messages; "t5s" / "spp16" for file names.
  std::string budget_text(double b) const;
  std::string budget_label(double b) const;
};

ExperimentConfig parse_experiment(const std::string& path);
// Parses text as if read from `path` (relative paths resolve against its folder).
ExperimentConfig parse_experiment_string(const std::string& text, const std::string& path);

// Lower-case letters, digits and '-' (every other run of characters becomes one '-').
std::string slugify(const std::string& name);

}  // namespace dp::experiments
