// `deltapath experiment FILE`: runs a YAML experiment (experiments/config.h).
#pragma once

#include <CLI/CLI.hpp>

namespace dp::apps {

void register_experiment(CLI::App& app);

}  // namespace dp::apps
