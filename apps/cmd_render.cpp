// `deltapath render SCENE ...`: renders a scene and writes FILE.exr (all layers),
// FILE.png (preview of the final image) and FILE.json (resolved settings, seed, wall
// time, samples, counters, partial flag). SIGINT/SIGTERM (apps/interrupt.h) stop at the
// next tile boundary and keep what was rendered, marked partial; main then exits 128 +
// signal. A signal while the scene loads exits at once with nothing written.
// `--partial` writes FILE.exr with the raw sums and counts instead (apps/partial_file.h)
// and FILE.json; `--part K/N` renders the K-th of N disjoint shares (tile_scheduler.h)
// for `deltapath merge` (issue 17), with --spp or --time. `--mpi` (or a start by mpirun
// with more than one rank) renders rank r's share and reduces the shares on rank 0
// (apps/mpi_render.h).
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/cli_checks.h"
#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/mpi_render.h"
#include "apps/output.h"
#include "apps/partial_file.h"
#include "core/error.h"
#include "core/log.h"
#include "core/timer.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"
#include "manifold/mesh_normals.h"
#include "scene/loaders/loader.h"

namespace dp::apps {

namespace {
struct RenderArgs {
  std::string scene, integrator, out = "render.exr";
  int spp = 0, threads = 0, max_depth = 0;
  double time = 0;
  uint64_t seed = 0;
  std::vector<std::string> sets;
  bool quiet = false;
  bool partial = false;
  std::string part;  // "K/N" (validated by part_spec)
  bool mpi = false;
};

// The facts of a --partial file (apps/partial_file.h) of this render.
core::Facts partial_facts(const RenderArgs& a, const std::string& hash, const std::string& name,
                          const integrators::Settings& settings, const integrators::RenderOptions& opt,
                          const integrators::RenderResult& result, int width, int height) {
  core::Facts f;
  f["integrator"] = name;
  for (const auto& [k, v] : settings.values()) f["setting." + k] = v;
  f["seed"] = std::to_string(int64_t(opt.seed));  // as the sidecar writes it
  f["spp"] = std::to_string(opt.time_budget > 0 ? 0 : opt.spp);  // 0: a --time render
  if (opt.time_budget > 0) f["time_budget"] = std::to_string(opt.time_budget);  // may differ between parts
  f["max_depth"] = std::to_string(opt.max_depth);
  f["width"] = std::to_string(width);
  f["height"] = std::to_string(height);
  f["scene_hash"] = hash;
  f["part"] = std::to_string(opt.part + 1);
  f["parts"] = std::to_string(opt.parts);
  f["scene"] = a.scene;
  f["interrupted"] = result.partial ? "true" : "false";
  f["wall_seconds"] = std::to_string(result.wall_seconds);
  f["threads"] = std::to_string(integrators::resolve_threads(opt));
  core::Json info = result.info;
  const double passes = info["passes"].number();
  f["passes"] = std::to_string(std::isfinite(passes) ? int64_t(passes) : int64_t(0));
  for (const auto& [k, v] : result.stats.counters()) f["counter." + k] = std::to_string(v);
  return f;
}

void run_render(const RenderArgs& a, const MpiWorld* world) {
  if (a.quiet || (world && world->rank > 0)) log::set_level(log::Level::warn);
  set_early_exit_message("interrupted while loading the scene; nothing written");
  core::Timer load_timer;
  const auto scene = scene::load_scene(a.scene, {manifold::normal_estimation_hook()});
  const double load_seconds = load_timer.seconds();
  const std::string hash = a.partial ? scene_hash(a.scene) : std::string();  // the bytes just loaded
  enable_graceful_stop();  // from here a first signal stops the render and keeps it
  const auto& defaults = scene->integrator_defaults();

  integrators::Settings settings;
  for (const auto& [k, v] : defaults.settings) settings.set(k, v, a.scene);
  for (const auto& kv : a.sets) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw ValueError("--set expects key=value, got '" + kv + "'", "command line");
    settings.set(kv.substr(0, eq), kv.substr(eq + 1), "--set");
  }
  const std::string name = a.integrator.empty() ? defaults.type : a.integrator;
  auto integrator = integrators::make_integrator(name, settings);

  integrators::RenderOptions opt;
  opt.spp = a.spp > 0 ? a.spp : (defaults.spp > 0 ? defaults.spp : 16);
  opt.time_budget = a.time;
  opt.seed = a.seed;
  opt.threads = a.threads;
  opt.max_depth = a.max_depth > 0 ? a.max_depth : defaults.max_depth;
  opt.quiet = a.quiet;
  opt.stop = stop_flag();
  if (opt.max_depth < 1) throw ValueError("--max-depth must be >= 1", "command line");
  if (a.time < 0) throw ValueError("--time must be positive", "command line");
  if (world) {
    if (!integrator->supports_raw())
      throw ValueError("integrator " + name + " does not support --mpi yet (path, volpath, gpt, bdpt, gbdpt, vcm, gpm, gvcm, mlt, memlt, gdmlt)", "command line");
    opt.raw = true;
    opt.part = world->rank;
    opt.parts = world->size;
    integrators::check_parts(scene->camera().width(), scene->camera().height(), opt);
  }
  if (a.partial) {
    if (!integrator->supports_raw())
      throw ValueError("integrator " + name + " does not support --partial yet", "command line");
    opt.raw = true;
    if (!a.part.empty()) {
      if (!parse_part(a.part, opt.part, opt.parts)) throw ValueError("bad --part '" + a.part + "'", "command line");
      opt.part -= 1;  // 0-based from here on
    }
    integrators::check_parts(scene->camera().width(), scene->camera().height(), opt);
  }

  integrators::check_scene_support(*integrator, *scene);
  log::info("rendering ", a.scene, " with ", name, " (", scene->camera().width(), "x", scene->camera().height(),
            a.time > 0 ? ", " + std::to_string(a.time) + " s" : ", " + std::to_string(opt.spp) + " spp", ")");
  integrators::RenderResult result = integrator->render(*scene, opt);
  // A signal after the last sample (e.g. during a gradient integrator's reconstruction)
  // still makes the result partial: the user asked to stop, the files say it was stopped.
  const int sig = received_signal();
  if (sig) result.partial = true;
  if (result.max_spp == 0 && (sig || a.time > 0)) {  // not one sample: a black image would be a lie
    if (sig) {
      log::warn("render interrupted by ", signal_name(sig), " before any sample was taken; nothing written");
      return;
    }
    char budget[32];
    std::snprintf(budget, sizeof(budget), "%g", a.time);
    throw Error(std::string("no samples were taken within --time ") + budget + "; nothing written (give a longer --time)",
                "command line");
  }
  if (result.partial) log::warn("render interrupted: writing the ", result.min_spp, "..", result.max_spp, " spp rendered so far");

  core::Json side = core::Json::object();
  if (a.partial) {
    side["part"] = std::to_string(opt.part + 1) + "/" + std::to_string(opt.parts);
    side["partial_file"] = true;  // FILE.exr holds raw sums and counts: `deltapath merge` them
  }
  side["scene"] = a.scene;
  side["integrator"] = name;
  side["settings"] = settings.to_json();
  side["seed"] = int64_t(a.seed);
  side["threads"] = integrators::resolve_threads(opt);
  side["max_depth"] = opt.max_depth;
  side["spp_requested"] = a.time > 0 ? core::Json(nullptr) : core::Json(opt.spp);
  side["time_budget"] = a.time > 0 ? core::Json(a.time) : core::Json(nullptr);
  side["load_seconds"] = load_seconds;
  side["interrupted_by"] = sig ? core::Json(signal_name(sig)) : core::Json(nullptr);
  if (world) {
    mpi_reduce_and_write(*world, *integrator, opt, result, side, a.out);
    return;
  }
  if (a.partial) {
    write_partial(a.out, result.raw, partial_facts(a, hash, name, settings, opt, result, scene->camera().width(),
                                                   scene->camera().height()));
    write_sidecar(a.out, result, side);
  } else {
    write_render_outputs(a.out, result, side);
  }
  if (sig)
    log::warn("wrote partial ", a.out, " (", result.min_spp, " spp); exiting with status ", interrupted_exit_status());
  else log::info("wrote ", a.out, " (", result.wall_seconds, " s, ", result.min_spp, " spp)");
}
}  // namespace

void register_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene (YAML or Mitsuba XML)");
  cmd->add_option("scene", args->scene, "scene file")->required();
  cmd->add_option("--integrator", args->integrator, "integrator (default: the scene's, else path)");
  auto* spp = cmd->add_option("--spp", args->spp, "samples per pixel (default: the scene's, else 16)")
                  ->check(sample_count());
  cmd->add_option("--time", args->time, "wall-clock budget in seconds (instead of --spp)")
      ->excludes(spp)
      ->check(seconds());
  cmd->add_option("--seed", args->seed, "random seed (default 0)");
  cmd->add_option("--threads", args->threads, "worker threads (default: all cores)")->check(thread_count());
  cmd->add_option("--max-depth", args->max_depth, "maximum path segments (default: the scene's, else 8)")
      ->check(path_depth());
  cmd->add_option("--set", args->sets, "integrator setting key=value (repeatable)");
  cmd->add_option("--out", args->out, "output EXR (also writes .png and .json beside it)");
  cmd->add_flag("--quiet", args->quiet, "no progress bar or info messages");
  auto* partial = cmd->add_flag("--partial", args->partial,
                                "write raw sums and sample counts for `deltapath merge` (every integrator)");
  cmd->add_option("--part", args->part, "render share K of N (1-based) for `merge`; needs --partial")
      ->check(part_spec())
      ->needs(partial);
  cmd->add_flag("--mpi", args->mpi,
                "split the render over the MPI ranks (implied when started by mpirun with > 1 rank); rank 0 "
                "writes the outputs (every integrator with --partial)")
      ->excludes(partial);
  cmd->callback([args] {
    if (!args->mpi && !under_mpirun()) return run_render(*args, nullptr);
    const MpiWorld world = mpi_start();
    try {
      run_render(*args, &world);
    } catch (const std::exception& e) {  // every rank ends: no rank waits for this one
      mpi_abort("rank " + std::to_string(world.rank) + ": " + e.what());
    }
    mpi_stop();
  });
}

}  // namespace dp::apps
