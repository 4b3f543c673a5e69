#include "integrators/gradient_output.h"

#include "core/timer.h"
#include "reconstruct/solve.h"

namespace dp::integrators {

void add_reconstruction_layers(const reconstruct::Problem& problem, const core::Image& direct,
                               const std::string& shown, int threads, RenderResult& result) {
  reconstruct::SolveOptions sopt;
  sopt.threads = threads;
  core::Timer solve_timer;
  core::Image l2 = reconstruct::solve_l2(problem, sopt).image;
  const double l2_seconds = solve_timer.seconds();
  solve_timer.reset();
  core::Image l1 = reconstruct::solve_l1(problem, sopt).image;
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
}

void add_gradient_layers(const core::Image& primal, const core::Image& dx, const core::Image& dy,
                         const core::Image& direct, float alpha, const std::string& shown, int threads,
                         RenderResult& result) {
  add_reconstruction_layers(reconstruct::make_grid_problem(primal, dx, dy, alpha), direct, shown, threads, result);
  result.layers.push_back({"dx", dx});
  result.layers.push_back({"dy", dy});
}

}  // namespace dp::integrators
