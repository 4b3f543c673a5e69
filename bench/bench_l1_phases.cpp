// Where the L1 grid solve's time goes (issue 18): the IRLS loop of solve_l1 (solve.h)
// for the forward-difference grid, rebuilt from the library's public pieces with a wall
// clock around each phase. Input: bench_reconstruct's l1_grid case (reconstruct_input.h).
// Prints one line per reweighting (CG iterations, CPU milliseconds per phase), the totals,
// and the cost of the CG set-up alone (mg_pcg with 0 iterations) and per iteration.
// Then the cost of one CG iteration alone: 15 runs of mg_pcg with 8 iterations (tolerance
// 0) from the last start, the fastest run (the least disturbed by other processes).
// Usage: bench_l1_phases [threads=2] [reweightings=20] [separate]
// (`separate`: set_irls_weights, rhs and mg_pcg's own start instead of the fused
// GridOperator::reweight_start that solve_l1 uses).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/reconstruct_input.h"
#include <ctime>
#include "reconstruct/grid_operator.h"
#include "reconstruct/multigrid.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;

namespace {

// Process CPU time (all threads): less sensitive to other processes on a shared machine
// than wall time (DP_BENCH_WALL=1 in the environment selects wall time).
class Clock {
 public:
  Clock() { reset(); }
  void reset() { m_start = now(); }
  double seconds() const { return now() - m_start; }

 private:
  static double now() {
    static const bool wall = std::getenv("DP_BENCH_WALL") != nullptr;
    timespec t{};
    clock_gettime(wall ? CLOCK_MONOTONIC : CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  double m_start = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int reweightings = argc > 2 ? std::atoi(argv[2]) : 20;
  const bool separate = argc > 3 && std::string(argv[3]) == "separate";
  const int w = 1280, h = 720;
  const core::Image truth = bench::truth_image(w, h);
  const Problem p = bench::noisy(Kernel::forward_differences(w, h), truth, 1);
  const SolveOptions o;  // the defaults solve_l1 uses
  const size_t n = p.kernel.pixels();

  const Clock total;
  Clock t;
  SolveOptions direct = o;
  direct.threads = threads;
  direct.method = L2Method::direct;
  const SolveResult l2 = solve_l2(p, direct);
  const double l2_ms = 1e3 * t.seconds();
  std::vector<Vec4> x(n), g(n), rhs(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = to_vec4(l2.image[i]);
    g[i] = to_vec4(p.primal[i]);
  }
  GridOperator A(w, h);
  A.set_factor_preconditioner(false);
  GridMultigrid M;
  CgWorkspace ws;
  double sum_weights = 0.0, sum_rhs = 0.0, sum_build = 0.0, sum_cg = 0.0, sum_setup = 0.0;
  int sum_it = 0;
  std::printf("reweighting,cg_iterations,weights_ms,rhs_ms,build_ms,cg_ms,cg_setup_ms\n");
  for (int it = 1; it <= reweightings; ++it) {
    const double reg = 0.05 * std::pow(0.5, it - 1);
    std::vector<Vec4d> row_rr(static_cast<size_t>(h)), row_bb(static_cast<size_t>(h));
    t.reset();
    if (separate) {
      A.set_irls_weights(x.data(), p.b, g.data(), reg, p.alpha, nullptr, nullptr, threads);
    } else {
      ws.r.resize(n);
      ws.z.resize(n);
      A.reweight_start(x.data(), p.b, g.data(), reg, p.alpha, nullptr, nullptr, ws.r.data(), nullptr,
                       row_rr.data(), row_bb.data(), threads);
    }
    const double weights_ms = 1e3 * t.seconds();
    t.reset();
    if (separate) A.rhs(p.b, g.data(), rhs.data(), threads);
    const double rhs_ms = 1e3 * t.seconds();
    t.reset();
    // As solve_l1: no hierarchy for a run that starts converged.
    const CgStart start{row_rr.data(), row_bb.data(), false};
    if (separate || !cg_start_converged(start, h, o.irls_cg_tolerance)) M.build(A, threads);
    const double build_ms = 1e3 * t.seconds();
    CgSettings s;
    s.max_iterations = o.irls_cg_iterations;
    s.tolerance = o.irls_cg_tolerance;
    s.threads = threads;
    // The set-up alone (residual, norms) on a copy: not part of the solve's time.
    double setup_ms = 0.0;
    if (separate) {
      std::vector<Vec4> copy = x;
      CgSettings zero = s;
      zero.max_iterations = 0;
      t.reset();
      mg_pcg(A, M, rhs.data(), copy.data(), zero, &ws);
      setup_ms = 1e3 * t.seconds();
    }
    t.reset();
    const CgStats st = mg_pcg(A, M, rhs.data(), x.data(), s, &ws, separate ? nullptr : &start);
    const double cg_ms = 1e3 * t.seconds();
    std::printf("%d,%d,%.1f,%.1f,%.1f,%.1f,%.1f\n", it, st.iterations, weights_ms, rhs_ms, build_ms, cg_ms, setup_ms);
    sum_weights += weights_ms;
    sum_rhs += rhs_ms;
    sum_build += build_ms;
    sum_cg += cg_ms;
    sum_setup += setup_ms;
    sum_it += st.iterations;
  }
  const double all_ms = 1e3 * total.seconds() - sum_setup;
  std::printf("# threads %d: total %.0f ms (without the set-up probes), initial L2 (DCT) %.0f, weights %.0f, rhs %.0f, "
              "build %.0f, CG %.0f (%d iterations; set-up %.0f, %.1f per iteration)\n",
              threads, all_ms, l2_ms, sum_weights, sum_rhs, sum_build, sum_cg, sum_it, sum_setup,
              sum_it > 0 ? (sum_cg - sum_setup) / sum_it : 0.0);
  {
    // Per-iteration cost on the last reweighted system, from the image reached.
    CgSettings s;
    s.max_iterations = 8;
    s.tolerance = 0.0;
    s.threads = threads;
    A.rhs(p.b, g.data(), rhs.data(), threads);
    M.build(A, threads);
    double best = 1e30;
    for (int rep = 0; rep < 15; ++rep) {
      std::vector<Vec4> copy = x;
      t.reset();
      const CgStats st = mg_pcg(A, M, rhs.data(), copy.data(), s, &ws);
      best = std::min(best, 1e3 * t.seconds() / std::max(1, st.iterations));
    }
    std::printf("# CG iteration alone (8 from the final image, best of 15, incl. set-up / 8): %.2f ms\n", best);
  }
  core::Image img(w, h);
  for (size_t i = 0; i < n; ++i) img[i] = to_rgb(x[i]);
  std::printf("# rmse vs truth %.5f\n", bench::rmse(img, truth));
  return 0;
}
