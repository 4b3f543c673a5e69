// Jacobi-preconditioned conjugate gradient on A x = rhs for the Laplacian operator
// (Lehtinen et al. 2013, Sec. 5: CG on the screened Poisson normal equations; Jacobi
// preconditioning matters once per-row / IRLS weights vary across the image).
// The three RGB channels are three independent CG recurrences sharing A (each channel
// has its own step sizes and stops on its own). Vectors are float (storage); every dot
// product is accumulated in double, per thread, and summed in a fixed order, so results
// are deterministic for a given thread count.
#pragma once

#include "reconstruct/laplacian.h"

namespace dp::reconstruct {

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

// x holds the initial guess (warm start) and receives the solution; rhs and x are RGB
// interleaved, 3 * A.pixels() floats.
CgStats pcg(const Laplacian& A, const float* rhs, float* x, const CgSettings& settings);

}  // namespace dp::reconstruct
