// Preconditioned conjugate gradient on A x = rhs for the screened Poisson normal
// equations (Lehtinen et al. 2013, Sec. 5). The three RGB channels are three
// independent CG recurrences sharing A (each channel has its own step sizes and stops on
// its own); vectors are Vec4 (vec4.h), the 4th lane stays 0.
//
// Parallel structure: the operator splits the pixels into fixed chunks of image rows.
// Each CG iteration is two phases, each a pass over all chunks handed out dynamically to
// the threads:
//   A: p = z + beta p_old and q = A p on the chunk (p of neighbouring chunks is formed
//      on the fly from z and p_old, so no pass of its own is needed), partial p.q;
//   B: x += alpha p, r -= alpha q, z = M^-1 r on the chunk, partials r.z and r.r.
// No barrier: whichever thread completes a phase's last chunk sums the per-chunk
// partials (in chunk order) and opens the next phase, so a thread descheduled by a busy
// machine only delays the chunk it holds, never a whole phase. Results are
// deterministic and independent of the thread count.
//
// The preconditioner M is block incomplete Cholesky: per chunk, the zero-fill
// factorization (D + L) D^-1 (D + L)^T of A restricted to the chunk (couplings to other
// chunks dropped, their weights kept on the diagonal), so applying it needs no data from
// other chunks. A is a weakly diagonally dominant M-matrix with a positive data term,
// which keeps every pivot positive (Meijerink & van der Vorst 1977).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "reconstruct/vec4.h"

namespace dp::reconstruct {

class ChunkedOperator {
 public:
  virtual ~ChunkedOperator() = default;
  virtual size_t pixels() const = 0;
  virtual size_t chunks() const = 0;
  // Chunk c covers pixels [chunk_begin(c), chunk_begin(c + 1)).
  virtual size_t chunk_begin(size_t c) const = 0;
  // Vec4 scratch the operator needs per thread in direction().
  virtual size_t scratch_size() const { return 0; }
  // out = A in on chunk c.
  virtual void apply(size_t c, const Vec4* in, Vec4* out) const = 0;
  // p_new = z + beta p_old and q = A p_new on chunk c; adds sum p_new . q to pq.
  virtual void direction(size_t c, const Vec4* z, const Vec4* p_old, Vec4 beta, Vec4* p_new, Vec4* q, Vec4d& pq,
                         Vec4* scratch) const = 0;
  // z = M^-1 r on chunk c (block incomplete Cholesky).
  virtual void precondition(size_t c, const Vec4* r, Vec4* z) const = 0;
  // CG phase B on chunk c: x += alpha p, r -= alpha q, z = M^-1 r; adds r.z to rz and
  // r.r to rr. Operators may override it with a fused, cache-friendlier version.
  virtual void update(size_t c, Vec4 alpha, const Vec4* p, const Vec4* q, Vec4* x, Vec4* r, Vec4* z, Vec4d& rz,
                      Vec4d& rr) const;
};

struct CgSettings {
  int max_iterations = 1000;
  // Stop a channel when ||rhs - A x||_2 <= tolerance * ||rhs||_2.
  double tolerance = 1e-6;
  int threads = 0;  // 0 = all hardware threads
};

struct CgStats {
  int iterations = 0;
  double relative_residual = 0.0;  // max over channels, from the recurrence
  bool converged = false;
};

// The stats of a 3-channel CG run after `iterations`: converged when no channel is still
// active; the residual relative to |b| per channel (absolute where b = 0), the largest.
template <class Flags, class Values>
CgStats cg_stats(int iterations, const Flags& active, const Values& rr, const Values& bb) {
  CgStats stats;
  stats.iterations = iterations;
  stats.converged = !(active[0] || active[1] || active[2]);
  for (int c = 0; c < 3; ++c)
    stats.relative_residual =
        std::max(stats.relative_residual, bb[c] > 0.0 ? std::sqrt(rr[c] / bb[c]) : std::sqrt(rr[c]));
  return stats;
}

// Scratch vectors of pcg(), kept between calls (IRLS solves many small CG runs: no
// reallocation and page faults each time).
struct CgWorkspace {
  std::vector<Vec4> r, z, q, pa, pb, scratch;
};

// x holds the initial guess (warm start) and receives the solution.
CgStats pcg(const ChunkedOperator& A, const Vec4* rhs, Vec4* x, const CgSettings& settings,
            CgWorkspace* workspace = nullptr);

// Splits `height` image rows into chunks of about `rows` rows: returns the first row of
// each chunk plus `height` at the end.
std::vector<int> row_chunks(int height, int rows);

// Image rows per chunk of the Laplacian and the grid operator: enough chunks for dynamic
// load balancing on a busy machine, blocks tall enough that the block preconditioner
// keeps most couplings (the screened Poisson Green's function decays over ~1/alpha = 5
// pixels at the default alpha).
constexpr int kChunkRows = 24;

}  // namespace dp::reconstruct
