#include "reconstruct/problem.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <string>

#include "core/error.h"

namespace dp::reconstruct {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw ValueError("reconstruct: " + message);
}

}  // namespace

Kernel::Kernel(int width, int height, std::vector<PixelPair> pairs)
    : m_width(width), m_height(height), m_pairs(std::move(pairs)) {
  require(width > 0 && height > 0, "kernel size must be positive, got " + std::to_string(width) + "x" +
                                       std::to_string(height));
  const int64_t n = int64_t(width) * int64_t(height);
  require(n <= int64_t(INT32_MAX), "image too large for 32-bit pixel indices");
  for (size_t r = 0; r < m_pairs.size(); ++r) {
    const PixelPair& p = m_pairs[r];
    require(p.i >= 0 && p.i < n && p.j >= 0 && p.j < n,
            "pair " + std::to_string(r) + " (" + std::to_string(p.i) + ", " + std::to_string(p.j) +
                ") is outside the " + std::to_string(width) + "x" + std::to_string(height) + " image");
    require(p.i != p.j, "pair " + std::to_string(r) + " joins pixel " + std::to_string(p.i) + " to itself");
  }
}

Kernel Kernel::forward_differences(int width, int height) {
  require(width > 0 && height > 0, "grid size must be positive");
  std::vector<PixelPair> pairs;
  pairs.reserve(size_t(width - 1) * size_t(height) + size_t(width) * size_t(height - 1));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x + 1 < width; ++x) pairs.push_back({y * width + x, y * width + x + 1});
  for (int y = 0; y + 1 < height; ++y)
    for (int x = 0; x < width; ++x) pairs.push_back({y * width + x, (y + 1) * width + x});
  Kernel k(width, height, std::move(pairs));
  k.m_grid = true;
  return k;
}

void validate(const Problem& problem) {
  const Kernel& k = problem.kernel;
  require(!problem.primal.empty(), "primal image is empty");
  require(problem.primal.width() == k.width() && problem.primal.height() == k.height(),
          "primal is " + std::to_string(problem.primal.width()) + "x" + std::to_string(problem.primal.height()) +
              " but the kernel is " + std::to_string(k.width()) + "x" + std::to_string(k.height()));
  require(problem.b.size() == k.rows(), "b has " + std::to_string(problem.b.size()) + " rows, kernel has " +
                                            std::to_string(k.rows()));
  require(std::isfinite(problem.alpha) && problem.alpha > 0.0f,
          "alpha must be finite and > 0, got " + std::to_string(problem.alpha));
  if (!problem.row_weights.empty()) {
    require(problem.row_weights.size() == k.rows(), "row_weights has " + std::to_string(problem.row_weights.size()) +
                                                        " entries, kernel has " + std::to_string(k.rows()) + " rows");
    for (float w : problem.row_weights) require(std::isfinite(w) && w >= 0.0f, "row weights must be finite and >= 0");
  }
  if (!problem.pixel_weights.empty()) {
    require(problem.pixel_weights.size() == k.pixels(),
            "pixel_weights has " + std::to_string(problem.pixel_weights.size()) + " entries, image has " +
                std::to_string(k.pixels()) + " pixels");
    for (float w : problem.pixel_weights) require(std::isfinite(w) && w > 0.0f, "pixel weights must be finite and > 0");
  }
}

Problem make_grid_problem(core::Image primal, const core::Image& dx, const core::Image& dy, float alpha) {
  require(!primal.empty(), "primal image is empty");
  require(primal.same_size(dx) && primal.same_size(dy),
          "primal, dx and dy must have the same size (primal " + std::to_string(primal.width()) + "x" +
              std::to_string(primal.height()) + ", dx " + std::to_string(dx.width()) + "x" +
              std::to_string(dx.height()) + ", dy " + std::to_string(dy.width()) + "x" + std::to_string(dy.height()) +
              ")");
  Problem p;
  p.kernel = Kernel::forward_differences(primal.width(), primal.height());
  p.b.resize(p.kernel.rows());
  const int w = primal.width(), h = primal.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x + 1 < w; ++x) p.b[p.kernel.grid_dx_row(x, y)] = dx(x, y);
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x < w; ++x) p.b[p.kernel.grid_dy_row(x, y)] = dy(x, y);
  p.primal = std::move(primal);
  p.alpha = alpha;
  validate(p);
  return p;
}

std::vector<Rgb> apply_kernel(const Kernel& kernel, const core::Image& image) {
  require(image.width() == kernel.width() && image.height() == kernel.height(), "image and kernel sizes differ");
  std::vector<Rgb> out(kernel.rows());
  for (size_t r = 0; r < out.size(); ++r) {
    const PixelPair& p = kernel.pairs()[r];
    out[r] = image[size_t(p.j)] - image[size_t(p.i)];
  }
  return out;
}

std::vector<float> reversed_pair_weights(const Kernel& kernel, float weight) {
  require(std::isfinite(weight) && weight >= 0.0f, "the weight of reversed pairs must be finite and >= 0");
  std::vector<std::pair<int32_t, int32_t>> sorted;
  sorted.reserve(kernel.rows());
  for (const PixelPair& p : kernel.pairs()) sorted.emplace_back(p.i, p.j);
  std::sort(sorted.begin(), sorted.end());
  std::vector<float> w(kernel.rows(), 1.0f);
  for (size_t r = 0; r < kernel.rows(); ++r) {
    const PixelPair& p = kernel.pairs()[r];
    if (std::binary_search(sorted.begin(), sorted.end(), std::make_pair(p.j, p.i))) w[r] = weight;
  }
  return w;
}

}  // namespace dp::reconstruct
