// Wall time of the screened Poisson solvers at 1280x720 (issue 4 targets on 2 cores:
// L2 grid direct <= 0.3 s, L2 PCG with 4 pairs per pixel <= 1.5 s, L1 with 20
// reweightings <= 3 s). Synthetic input: a smooth image with edges, primal noise
// sigma 0.2, gradient noise sigma 0.02 (fixed seed). Prints CSV on stdout:
//   case,width,height,threads,seconds,cg_iterations,relative_residual,rmse
// Grid cases use the multigrid-preconditioned CG; the *_ic cases the block incomplete
// Cholesky one (SolveOptions::grid_solver, issue 18).
// Usage: bench_reconstruct [threads=2] [repeats=3] [case filter substring]
// (the median over repeats is printed, then the minimum, then the median process CPU
// time, which depends less on what else runs on the machine).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <ctime>
#include <vector>

#include "bench/reconstruct_input.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using dp::bench::rmse;

namespace {

// Forward differences plus both diagonals: 4 pairs per pixel (fewer at the border).
Kernel four_pair_kernel(int w, int h) {
  std::vector<PixelPair> pairs;
  pairs.reserve(size_t(4) * size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = y * w + x;
      if (x + 1 < w) pairs.push_back({i, i + 1});
      if (y + 1 < h) pairs.push_back({i, i + w});
      if (x + 1 < w && y + 1 < h) pairs.push_back({i, i + w + 1});
      if (x > 0 && y + 1 < h) pairs.push_back({i, i + w - 1});
    }
  return Kernel(w, h, std::move(pairs));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size();
  return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int repeats = std::max(1, argc > 2 ? std::atoi(argv[2]) : 3);
  const std::string filter = argc > 3 ? argv[3] : "";
  const int w = 1280, h = 720;
  const core::Image truth = bench::truth_image(w, h);
  const Problem grid = bench::noisy(Kernel::forward_differences(w, h), truth, 1);
  const Problem four = bench::noisy(four_pair_kernel(w, h), truth, 2);
  std::printf("case,width,height,threads,seconds,cg_iterations,relative_residual,rmse,min_seconds,cpu_seconds\n");
  const auto run = [&](const char* name, const Problem& p, bool l1, L2Method method,
                       GridSolver grid_solver = GridSolver::multigrid) {
    if (std::string(name).find(filter) == std::string::npos) return;
    SolveOptions o;
    o.threads = threads;
    o.method = method;
    o.grid_solver = grid_solver;
    SolveResult last;
    std::vector<double> seconds, cpu;
    for (int r = 0; r < repeats; ++r) {
      const double c0 = cpu_seconds();
      last = l1 ? solve_l1(p, o) : solve_l2(p, o);
      cpu.push_back(cpu_seconds() - c0);
      seconds.push_back(last.seconds);
    }
    std::printf("%s,%d,%d,%d,%.4f,%d,%.3g,%.5f,%.4f,%.4f\n", name, w, h, threads, median(seconds), last.cg_iterations,
                last.relative_residual, rmse(last.image, truth), *std::min_element(seconds.begin(), seconds.end()),
                median(cpu));
    std::fflush(stdout);
  };
  std::printf("# primal rmse %.5f\n", rmse(grid.primal, truth));
  run("l2_grid_dct", grid, false, L2Method::direct);
  run("l2_pcg_4pairs", four, false, L2Method::cg);
  run("l2_grid_pcg", grid, false, L2Method::cg);
  run("l2_grid_pcg_ic", grid, false, L2Method::cg, GridSolver::block_ic);
  run("l1_grid_irls20", grid, true, L2Method::automatic);
  run("l1_grid_irls20_ic", grid, true, L2Method::automatic, GridSolver::block_ic);
  run("l1_4pairs_irls20", four, true, L2Method::automatic);
  return 0;
}
