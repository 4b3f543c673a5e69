// The screened Poisson problem of a pair kernel (Manzi et al. 2014, Eq. 8):
//     min_I  |H I - b|^2 + alpha^2 |I - I_g|^2,
// row r of H being the kernel's row {a, b}: (H I)_r = I[b] - I[a] (reconstruct/problem.h),
// and b the accumulated per-row RGB values (the splats of pair_kernel.h, divided by the
// sample normalisation the caller uses). Solve it with reconstruct::solve_l2 (CG on the
// graph Laplacian for adaptive kernels, DCT for the standard grid) or solve_l1 (IRLS).
#pragma once

#include <vector>

#include "core/image.h"
#include "kernels_adaptive/pair_kernel.h"
#include "reconstruct/problem.h"

namespace dp::kernels_adaptive {

// The reconstruct::Kernel with the same rows. When the rows are exactly the
// forward-difference grid (standard_kernel) it is Kernel::forward_differences, so the
// solver may take its exact DCT path. Throws dp::ValueError for invalid rows.
reconstruct::Kernel to_reconstruct_kernel(const PairKernel& kernel);

// Throws dp::ValueError if the primal's size differs from the kernel's or row_values
// does not have one value per row; alpha is checked by reconstruct::validate.
reconstruct::Problem make_problem(const PairKernel& kernel, core::Image primal, std::vector<Rgb> row_values,
                                  float alpha = reconstruct::kDefaultAlpha);

}  // namespace dp::kernels_adaptive
