// deltapath: command-line front end (render, info, compare, layer, reconstruct, experiment, stress).
#include <cstdio>
#include <exception>
#include <new>

#include "apps/cmd_experiment.h"
#include "apps/cmd_reconstruct.h"
#include "apps/cmd_stress.h"
#include "apps/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"Deltapath: gradient-domain light transport"};
  app.require_subcommand(1);
  dp::apps::register_render(app);
  dp::apps::register_info(app);
  dp::apps::register_compare(app);
  dp::apps::register_layer(app);
  dp::apps::register_reconstruct(app);
  dp::apps::register_experiment(app);
  dp::apps::register_stress(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const dp::Error& e) {
    std::fprintf(stderr, "deltapath: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "deltapath: error: out of memory (the scene or image is too large for this machine)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deltapath: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
