// Exact direct solve of (c H^T H + s I) x = rhs for the forward-difference grid kernel
// with Neumann boundaries (Bhat et al. 2008, "Fourier analysis of the 2D screened
// Poisson equation", Sec. 4; ALGORITHMS.md): H^T H is diagonalized by the 2D DCT-II,
//     x^(u,v) = rhs^(u,v) / (s - c lambda(u,v)),
//     lambda(u,v) = 2 cos(pi u / W) + 2 cos(pi v / H) - 4.
// For the unweighted screened Poisson problem c = 1 and s = alpha^2. FFTW single
// precision (REDFT10 = DCT-II forward, REDFT01 = DCT-III inverse, FFTW_ESTIMATE plans);
// the channels are transformed in parallel.
#pragma once

namespace dp::reconstruct {

// rhs and x are RGB interleaved (3 * width * height floats); they may alias.
// Requires c >= 0, s > 0.
void dct_solve(int width, int height, const float* rhs, float* x, double c, double s, int threads);

}  // namespace dp::reconstruct
