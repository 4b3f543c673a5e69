// Shared helpers for the reconstruct tests: test images, random kernels, and an
// independent dense (double, Eigen) assembly of the normal equations.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "core/image.h"
#include "core/rng.h"
#include "reconstruct/laplacian.h"
#include "reconstruct/pcg.h"
#include "reconstruct/vec4.h"
#include "reconstruct/problem.h"

namespace dp::reconstruct::test {

// Random 3-channel vectors (4th lane 0), and A applied chunk by chunk.
inline std::vector<Vec4> random_vec4(size_t n, core::Rng& rng) {
  std::vector<Vec4> v(n);
  for (auto& x : v) x = Vec4{rng.uniform() - 0.5f, rng.uniform(), 2.0f * rng.uniform() - 1.0f, 0.0f};
  return v;
}
inline std::vector<Vec4> apply_all(const ChunkedOperator& A, const std::vector<Vec4>& in) {
  std::vector<Vec4> out(in.size());
  for (size_t c = 0; c < A.chunks(); ++c) A.apply(c, in.data(), out.data());
  return out;
}

// Smooth ramps plus a hard edge and a bright square: gradients of every size.
inline core::Image test_image(int w, int h) {
  core::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float u = float(x) / float(w), v = float(y) / float(h);
      Rgb c(0.2f + 0.5f * u, 0.3f + 0.4f * v * v, 0.5f + 0.3f * std::sin(6.0f * u + 3.0f * v));
      if (x > w / 2) c += Rgb(0.4f, 0.1f, 0.0f);
      if (x > w / 4 && x < w / 3 && y > h / 4 && y < h / 2) c = Rgb(2.0f, 1.5f, 1.0f);
      img(x, y) = c;
    }
  return img;
}

inline double gaussian(core::Rng& rng) {
  // Box-Muller.
  const double u1 = 1.0 - rng.uniform_double(), u2 = rng.uniform_double();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPiD * u2);
}

// Manzi-2014-like kernel: each pixel pairs with `per_pixel` random pixels in a 5x5
// window, plus long-range pairs, a duplicated pair and a reversed pair.
inline Kernel random_kernel(int w, int h, int per_pixel, core::Rng& rng) {
  std::vector<PixelPair> pairs;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < per_pixel; ++k) {
        int nx, ny;
        do {
          nx = std::clamp(x + int(rng.uniform_index(5)) - 2, 0, w - 1);
          ny = std::clamp(y + int(rng.uniform_index(5)) - 2, 0, h - 1);
        } while (nx == x && ny == y);
        pairs.push_back({y * w + x, ny * w + nx});
      }
  for (int k = 0; k < 5; ++k) {
    const int a = int(rng.uniform_index(uint32_t(w * h))), b = int(rng.uniform_index(uint32_t(w * h)));
    if (a != b) pairs.push_back({a, b});
  }
  pairs.push_back(pairs.front());
  pairs.push_back({pairs[1].j, pairs[1].i});
  return Kernel(w, h, std::move(pairs));
}

// Independent dense assembly of H^T W H + alpha^2 P (double).
inline Eigen::MatrixXd dense_matrix(const Kernel& k, const std::vector<float>& rw, const std::vector<float>& pw,
                                    double alpha) {
  const Eigen::Index n = Eigen::Index(k.pixels());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (size_t r = 0; r < k.rows(); ++r) {
    const auto [i, j] = k.pairs()[r];
    const double w = rw.empty() ? 1.0 : double(rw[r]);
    A(i, i) += w;
    A(j, j) += w;
    A(i, j) -= w;
    A(j, i) -= w;
  }
  for (Eigen::Index i = 0; i < n; ++i) A(i, i) += alpha * alpha * (pw.empty() ? 1.0 : double(pw[size_t(i)]));
  return A;
}

// Dense solution of the weighted L2 problem, one channel at a time (LDLT, double).
inline core::Image dense_solve(const Problem& p) {
  const Eigen::MatrixXd A = dense_matrix(p.kernel, p.row_weights, p.pixel_weights, double(p.alpha));
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  const double a2 = double(p.alpha) * double(p.alpha);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      rhs(i, c) = a2 * (p.pixel_weights.empty() ? 1.0 : double(p.pixel_weights[size_t(i)])) *
                  double(p.primal[size_t(i)][c]);
  for (size_t r = 0; r < p.kernel.rows(); ++r) {
    const auto [i, j] = p.kernel.pairs()[r];
    const double w = p.row_weights.empty() ? 1.0 : double(p.row_weights[r]);
    for (int c = 0; c < 3; ++c) {
      rhs(j, c) += w * double(p.b[r][c]);
      rhs(i, c) -= w * double(p.b[r][c]);
    }
  }
  const Eigen::MatrixXd x = A.ldlt().solve(rhs);
  core::Image out(p.kernel.width(), p.kernel.height());
  for (Eigen::Index i = 0; i < n; ++i) out[size_t(i)] = Rgb(float(x(i, 0)), float(x(i, 1)), float(x(i, 2)));
  return out;
}

// The operator as a dense matrix, by applying it to unit vectors (channel 0).
inline Eigen::MatrixXd operator_matrix(const Laplacian& L) {
  const size_t n = L.pixels();
  const auto dim = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd M(dim, dim);
  std::vector<float> e(3 * n, 0.0f), out(3 * n);
  for (size_t k = 0; k < n; ++k) {
    e[3 * k] = 1.0f;
    L.apply(e.data(), out.data(), 0, n);
    for (size_t i = 0; i < n; ++i) M(Eigen::Index(i), Eigen::Index(k)) = double(out[3 * i]);
    e[3 * k] = 0.0f;
  }
  return M;
}

inline double max_abs_diff(const core::Image& a, const core::Image& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    m = std::max(m, double((a[i] - b[i]).abs().maxCoeff()));
  return m;
}

// L1 objective of Lehtinen 2013 (group norms over RGB).
inline double l1_objective(const Problem& p, const core::Image& img) {
  double s = 0.0;
  const std::vector<Rgb> hx = apply_kernel(p.kernel, img);
  for (size_t r = 0; r < hx.size(); ++r) s += double((hx[r] - p.b[r]).matrix().norm());
  for (size_t i = 0; i < img.size(); ++i) s += double(p.alpha) * double((img[i] - p.primal[i]).matrix().norm());
  return s;
}

}  // namespace dp::reconstruct::test
