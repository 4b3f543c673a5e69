// The HTML report of an experiment: <output>/report.html with its images in
// <output>/report/ — the reference, each run's image at the largest budget (seed 0),
// its false-colour per-pixel error map (scoring.h), the crops side by side, the
// convergence plot, a per-budget summary (mean over seeds) and the full CSV table.
// Self-contained: relative links only, no scripts, fonts or other network resources.
#pragma once

#include <string>

#include "core/image.h"
#include "experiments/config.h"
#include "experiments/runner.h"

namespace dp::experiments {

// Returns the path of report.html.
std::string write_report(const ExperimentConfig& config, const ExperimentResult& result, const core::Image& reference);

std::string html_escape(const std::string& s);

}  // namespace dp::experiments
