// deltapath: command-line front end (render, merge, info, compare, layer, reconstruct, experiment, stress).
#include <cstdio>
#include <exception>
#include <new>

#include "apps/cmd_experiment.h"
#include "apps/cmd_reconstruct.h"
#include "apps/cmd_stress.h"
#include "apps/commands.h"
#include "apps/interrupt.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"Deltapath: gradient-domain light transport"};
  app.require_subcommand(1);
  dp::apps::register_render(app);
  dp::apps::register_info(app);
  dp::apps::register_compare(app);
  dp::apps::register_layer(app);
  dp::apps::register_merge(app);
  dp::apps::register_reconstruct(app);
  dp::apps::register_experiment(app);
  dp::apps::register_stress(app);
  // Before any command runs (so before scene loading): SIGINT/SIGTERM never leave a
  // half-written file, and interrupted commands exit 128 + signal (apps/interrupt.h).
  dp::apps::install_signal_handlers();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const dp::Error& e) {
    std::fprintf(stderr, "deltapath: %s\n", e.what());
    if (const int status = dp::apps::interrupted_exit_status()) return status;  // e.g. an interrupted experiment
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "deltapath: error: out of memory (the scene or image is too large for this machine)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deltapath: error: %s\n", e.what());
    return 2;
  }
  return dp::apps::interrupted_exit_status();  // 0, or 130/143 after writing a partial result
}
