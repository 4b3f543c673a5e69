#include "kernels_adaptive/kernel_problem.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/error.h"

namespace dp::kernels_adaptive {

reconstruct::Kernel to_reconstruct_kernel(const PairKernel& kernel) {
  if (kernel.width > 0 && kernel.height > 0) {
    reconstruct::Kernel grid = reconstruct::Kernel::forward_differences(kernel.width, kernel.height);
    const auto& g = grid.pairs();
    if (g.size() == kernel.rows.size() &&
        std::equal(g.begin(), g.end(), kernel.rows.begin(),
                   [](const reconstruct::PixelPair& x, const reconstruct::PixelPair& y) { return x.i == y.i && x.j == y.j; }))
      return grid;
  }
  return reconstruct::Kernel(kernel.width, kernel.height, kernel.rows);
}

reconstruct::Problem make_problem(const PairKernel& kernel, core::Image primal, std::vector<Rgb> row_values,
                                  float alpha) {
  if (primal.width() != kernel.width || primal.height() != kernel.height)
    throw ValueError("kernels_adaptive: primal is " + std::to_string(primal.width()) + "x" +
                     std::to_string(primal.height()) + ", kernel is " + std::to_string(kernel.width) + "x" +
                     std::to_string(kernel.height));
  if (row_values.size() != kernel.rows.size())
    throw ValueError("kernels_adaptive: " + std::to_string(row_values.size()) + " row values for " +
                     std::to_string(kernel.rows.size()) + " kernel rows");
  reconstruct::Problem p;
  p.primal = std::move(primal);
  p.kernel = to_reconstruct_kernel(kernel);
  p.b = std::move(row_values);
  p.alpha = alpha;
  reconstruct::validate(p);
  return p;
}

}  // namespace dp::kernels_adaptive
