// results.csv: one row per (run, budget, seed), columns
//   name, budget, seed, wall_time, spp, <one column per metric (Metric::column())>
// budget is seconds or spp as in the experiment file; wall_time is seconds; spp is the
// per-pixel sample count actually rendered (the minimum over pixels). Fields containing
// commas or quotes are quoted (RFC 4180).
#pragma once

#include <string>
#include <vector>

#include "experiments/config.h"
#include "experiments/runner.h"

namespace dp::experiments {

std::string csv_field(const std::string& s);
std::string results_csv_text(const ExperimentConfig& config, const std::vector<PointResult>& points);
// Writes atomically (temporary file + rename).
void write_results_csv(const std::string& path, const ExperimentConfig& config, const std::vector<PointResult>& points);

}  // namespace dp::experiments
