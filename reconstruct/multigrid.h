// Multigrid-preconditioned CG for the grid operator A = H^T W H + alpha^2 P of the
// forward-difference kernel (grid_operator.h): the inner solver of the L1 IRLS on grids.
//
// Hierarchy: 2x2 aggregation with the Galerkin coarse operator. With the piecewise-
// constant prolongation P (a coarse pixel's value copied to its 2x2 fine block) and the
// restriction R = P^T (sum over the block), P^T A P of a weighted 5-point graph
// Laplacian plus a diagonal is again one: the weight of a coarse dx edge is the sum of
// the two fine dx edges that cross between the blocks, likewise dy, and the coarse data
// term is the sum of the block's four data terms (edges inside a block cancel). So every
// level keeps the index-free per-pixel layout of GridOperator, with no fill-in, and
// jumps of the IRLS weights are coarsened exactly instead of being averaged away.
// Levels stop at a few thousand pixels: the data term alpha^2 P grows 4x per level
// against the edges' 2x, so the coarse problems are strongly diagonally dominant.
//
// Smoother: red-black Gauss-Seidel; pre-smoothing red then black, post-smoothing black
// then red, and the coarsest level by a palindromic sequence of sweeps, so the V-cycle is
// a symmetric positive definite preconditioner (as CG needs).
//
// Parallel structure: the threads split every level's rows; steps that read a
// neighbour's rows are separated by a barrier. Levels below serial_pixels are run by one
// thread (fewer barriers: they are cheap and a descheduled thread would stall each one).
// Results do not depend on the thread count: every update reads the same values in any
// split, restriction sums are formed in a fixed order, and reductions are summed per row
// in row order.
//
// CG is the same three per-channel recurrences as pcg() (pcg.h): a channel stops when
// ||rhs - A x||_2 <= tolerance ||rhs||_2 (its x is then frozen).
#pragma once

#include <functional>
#include <vector>

#include "reconstruct/grid_operator.h"
#include "reconstruct/pcg.h"
#include "reconstruct/vec4.h"

namespace dp::reconstruct {

class GridMultigrid {
 public:
  struct Level {
    int w = 0, h = 0;
    // Level 0 points into the GridOperator; coarser levels own their arrays.
    const float* wx = nullptr;
    const float* wy = nullptr;
    const float* diag = nullptr;
    const float* data = nullptr;
    const float* inv_diag = nullptr;
    std::vector<float> own_wx, own_wy, own_diag, own_data, own_inv_diag;
    std::vector<Vec4> x, b;  // coarse levels: correction and right-hand side
  };

  // Builds the hierarchy from A's current weights (call again after A's weights change;
  // A must outlive the solves). Vectors keep their allocation across rebuilds.
  void build(const GridOperator& A, int threads);

  // z = M^-1 r: one V-cycle from z = 0. Single-threaded convenience (tests).
  void apply(const Vec4* r, Vec4* z);

  // Smoothing sweeps per side on levels above the coarsest, and on the coarsest.
  int pre_sweeps = 2;
  int coarsest_sweeps = 4;
  // Coarsening stops at this many pixels; levels below serial_pixels run on one thread
  // (set before build(); tests lower them to get many levels on small images).
  size_t coarsest_pixels = 4096;
  size_t serial_pixels = 40000;

  const std::vector<Level>& levels() const { return m_levels; }

  // One thread's share of the V-cycle z = M^-1 r. Level-l rows of thread t are
  // [rows[t] >> l, rows[t+1] >> l) (rows[] multiples of 2^(levels-1) up to the serial
  // levels). `sync` waits for all `threads` threads; the caller synchronizes before (r
  // complete) and after (z complete). With first_red_done, z already holds the first red
  // half-sweep (z = r / d on red pixels, 0 on black ones: mg_pcg fuses it into the CG
  // update). If row_dot != nullptr, row_dot[y] = sum over row y of r . z.
  void vcycle(const Vec4* r, Vec4* z, const std::vector<int>& rows, int t, int threads,
              const std::function<void()>& sync, bool first_red_done, Vec4d* row_dot);

  // Row alignment vcycle() needs of the level-0 thread split.
  int row_alignment() const;

 private:
  void cycle(size_t l, const Vec4* b, Vec4* x, const std::vector<int>& rows, int t, int threads,
             const std::function<void()>& sync, bool first_red_done, Vec4d* row_dot);
  std::vector<Level> m_levels;
  size_t m_built_coarsest = 0;
};

// A CG start computed by the caller (GridOperator::reweight_start): the workspace's r
// holds rhs - A x, its z (if first_red_done) the V-cycle's first red half-step of r
// (r / d on the pixels with (x + y) even, 0 on the others), and row_rr / row_bb per image
// row the sums of r.r and rhs.rhs.
struct CgStart {
  const Vec4d* row_rr = nullptr;
  const Vec4d* row_bb = nullptr;
  bool first_red_done = true;  // false: z is not read (the first V-cycle forms it)
};

// Whether mg_pcg from `start` stops at once: every channel's ||r|| <= tolerance ||rhs||
// (the same test, on the same sums). Such a run reads neither the workspace nor the
// multigrid hierarchy.
bool cg_start_converged(const CgStart& start, int height, double tolerance);

// Multigrid-preconditioned CG on A x = rhs (x = initial guess, warm start). `M` must have
// been built from A's current weights. With `start` (which needs `workspace`), rhs is not
// read and the start is taken from the workspace and `start`.
CgStats mg_pcg(const GridOperator& A, GridMultigrid& M, const Vec4* rhs, Vec4* x, const CgSettings& settings,
               CgWorkspace* workspace = nullptr, const CgStart* start = nullptr);

}  // namespace dp::reconstruct
