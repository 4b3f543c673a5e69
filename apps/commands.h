// Subcommands of the `deltapath` CLI. Each registers itself on the CLI11 app; its
// callback throws dp::Error for problems a user can cause (printed as one line by main).
#pragma once

#include <CLI/CLI.hpp>

namespace dp::apps {

void register_render(CLI::App& app);
void register_info(CLI::App& app);
void register_compare(CLI::App& app);
void register_layer(CLI::App& app);
void register_merge(CLI::App& app);

}  // namespace dp::apps
