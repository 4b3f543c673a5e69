// Solvers for reconstruct::Problem (problem.h).
//
// solve_l2: the minimizer of sum_r w_r |(H I - b)_r|^2 + alpha^2 sum_i p_i |I_i - I_g,i|^2,
//   i.e. the normal equations (H^T W H + alpha^2 P) I = H^T W b + alpha^2 P I_g
//   (Lehtinen et al. 2013, Eq. 8; unbiased when b and I_g are). Forward-difference grid
//   kernels with uniform weights use the exact DCT solve (Bhat et al. 2008); everything
//   else uses preconditioned CG warm-started from the primal: on the index-free
//   GridOperator for grid kernels, preconditioned by a multigrid V-cycle (multigrid.h;
//   SolveOptions::grid_solver selects the block incomplete Cholesky instead), and on the
//   CSR Laplacian with block incomplete Cholesky (pcg.h) for any other kernel.
// solve_l1: the group-L1 problem sum_r |(H I - b)_r|_2 + sum_i alpha |I_i - I_g,i|_2
//   (norms over RGB; Lehtinen 2013 Sec. 5, robust but biased) by iteratively reweighted
//   least squares as in the reference solver (ALGORITHMS.md): iteration 0 is the L2
//   solve; iteration k >= 1 sets reg = 0.05 * 0.5^(k-1) and per-row weights
//   1 / (|e_r|_2 + reg) for every gradient row and every primal row (e = residual of
//   that row at the current image), normalizes them to mean 1, multiplies in the user's
//   weights, and continues CG from the current image (warm start). (The grid path leaves
//   out the normalization, which scales the system and its right-hand side alike.)
//
// Bad input: dp::ValueError for inconsistent sizes, alpha <= 0 and invalid weights.
// NaN/Inf in the primal or in b are data, not errors: a row of b with a non-finite
// channel is dropped (weight 0); a primal pixel with a non-finite channel loses its
// data term (p_i = 0) unless nothing else constrains its connected component, in which
// case it is anchored to 0. Both are counted in SolveResult::input and logged; the
// output never contains them.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "reconstruct/problem.h"

namespace dp::reconstruct {

enum class L2Method {
  automatic,  // DCT when the kernel is the forward-difference grid with uniform weights
  direct,     // DCT, dp::ValueError if not applicable
  cg,         // preconditioned CG on the graph Laplacian (any kernel)
};

// Preconditioner of CG on forward-difference grid kernels (L1 IRLS on grids, weighted
// or method == cg L2 grid solves). Both stop at the same relative residual; multigrid
// needs ~3x fewer iterations (bench/RESULTS.md, issue 18).
enum class GridSolver {
  multigrid,  // geometric multigrid V-cycle, Galerkin 2x2 aggregation (multigrid.h)
  block_ic,   // block incomplete Cholesky, barrier-free chunked CG (pcg.h)
};

struct SolveOptions {
  int threads = 0;  // 0 = all hardware threads
  L2Method method = L2Method::automatic;
  GridSolver grid_solver = GridSolver::multigrid;
  // L2 CG: stop when ||rhs - A I|| <= cg_tolerance ||rhs|| per channel (the DCT is
  // exact). 1e-6 is near the float-storage floor and keeps CG within ~1e-6 of the
  // exact solution on [0, 1]-range images.
  double cg_tolerance = 1e-6;
  int cg_max_iterations = 2000;
  // L1: reweightings after the initial L2 solve (reference: 20), each followed by at
  // most irls_cg_iterations warm-started CG iterations (reference: 50) or until the
  // relative residual drops below irls_cg_tolerance.
  int reweightings = 20;
  int irls_cg_iterations = 50;
  double irls_cg_tolerance = 1e-4;
  // Interrupts (issue 18): when this flag is set, solve_l1 stops before its next
  // reweighting and returns its current iterate (the L2 solution or a later IRLS image,
  // each a complete image), with SolveResult::interrupted. A reweighting at 1280x720
  // takes ~0.1 s, so a signal is honoured within about that.
  const std::atomic<bool>* stop = nullptr;
};

struct InputReport {
  int64_t nonfinite_primal_pixels = 0;  // primal pixels with a NaN/Inf channel
  int64_t nonfinite_rows = 0;           // rows of b with a NaN/Inf channel (dropped)
  int64_t anchored_pixels = 0;          // of those primal pixels, anchored to 0
};

struct SolveResult {
  core::Image image;
  InputReport input;
  std::string method;              // "dct", "pcg", "irls+dct", "irls+pcg"
  std::string preconditioner;      // of the CG runs: "multigrid", "block_ic" or "" (none ran)
  int cg_iterations = 0;           // total over all CG runs
  int reweightings = 0;            // L1 only: the reweightings done
  bool interrupted = false;        // L1 only: stopped by SolveOptions::stop before the last
  double relative_residual = 0.0;  // of the last CG run (0 for the DCT)
  double seconds = 0.0;            // wall time (steady clock)
};

SolveResult solve_l2(const Problem& problem, const SolveOptions& options = {});
SolveResult solve_l1(const Problem& problem, const SolveOptions& options = {});

}  // namespace dp::reconstruct
