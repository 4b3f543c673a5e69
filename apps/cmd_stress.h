// `deltapath stress [--quick]`: numerical-stability run (experiments/stress.h).
#pragma once

#include <CLI/CLI.hpp>

namespace dp::apps {

void register_stress(CLI::App& app);

}  // namespace dp::apps
