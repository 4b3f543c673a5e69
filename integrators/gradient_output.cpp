#include "integrators/gradient_output.h"

#include "core/log.h"
#include "core/timer.h"
#include "integrators/tile_scheduler.h"
#include "reconstruct/solve.h"

namespace dp::integrators {

void add_reconstruction_layers(const reconstruct::Problem& problem, const core::Image& direct,
                               const std::string& shown, const RenderOptions& options, RenderResult& result) {
  reconstruct::SolveOptions sopt;
  sopt.threads = resolve_threads(options);
  sopt.stop = options.stop;
  // Progress output (and the cue tests/cli/test_interrupt.sh waits for): at 1280x720 the
  // two solves take ~2 s, during which the progress bar has already finished.
  log::info("reconstructing ", problem.kernel.width(), "x", problem.kernel.height(), ": L2, then L1 (",
            sopt.reweightings, " reweightings)");
  core::Timer solve_timer;
  core::Image l2 = reconstruct::solve_l2(problem, sopt).image;
  const double l2_seconds = solve_timer.seconds();
  solve_timer.reset();
  reconstruct::SolveResult l1_result = reconstruct::solve_l1(problem, sopt);
  core::Image l1 = std::move(l1_result.image);
  const double l1_seconds = solve_timer.seconds();
  l2 += direct;
  l1 += direct;
  core::Image primal_full = problem.primal;
  primal_full += direct;
  result.layers.push_back({"", shown == "l2" ? l2 : l1});
  result.layers.push_back({"recon_l1", std::move(l1)});
  result.layers.push_back({"recon_l2", std::move(l2)});
  result.layers.push_back({"primal", std::move(primal_full)});
  result.layers.push_back({"direct", direct});
  result.info["solve_l2_seconds"] = l2_seconds;
  result.info["solve_l1_seconds"] = l1_seconds;
  result.info["solve_l1_reweightings"] = l1_result.reweightings;
  if (l1_result.interrupted) {
    result.info["reconstruction_interrupted"] = true;
    result.partial = true;
  }
}

void add_gradient_layers(const core::Image& primal, const core::Image& dx, const core::Image& dy,
                         const core::Image& direct, float alpha, const std::string& shown,
                         const RenderOptions& options, RenderResult& result) {
  add_reconstruction_layers(reconstruct::make_grid_problem(primal, dx, dy, alpha), direct, shown, options, result);
  result.layers.push_back({"dx", dx});
  result.layers.push_back({"dy", dy});
}

}  // namespace dp::integrators
