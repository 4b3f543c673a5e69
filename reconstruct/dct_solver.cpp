#include "reconstruct/dct_solver.h"

#include <fftw3.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "reconstruct/laplacian.h"

namespace dp::reconstruct {

namespace {

// FFTW's planner is not thread-safe (executing a plan is): every plan creation and
// destruction in this library goes through this lock.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

struct FftwFree {
  void operator()(float* p) const { fftwf_free(p); }
};
using FftwBuffer = std::unique_ptr<float, FftwFree>;

class Plan {
 public:
  Plan(int width, int height, float* buffer, fftwf_r2r_kind kind) {
    std::lock_guard<std::mutex> lock(planner_mutex());
    // Row-major: n0 = height (slow), n1 = width (fast).
    m_plan = fftwf_plan_r2r_2d(height, width, buffer, buffer, kind, kind, FFTW_ESTIMATE);
    DP_CHECK(m_plan != nullptr, "FFTW could not create a DCT plan");
  }
  ~Plan() {
    std::lock_guard<std::mutex> lock(planner_mutex());
    fftwf_destroy_plan(m_plan);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
  // New-array execute: buffers come from fftwf_malloc, so they share the alignment.
  void run(float* buffer) const { fftwf_execute_r2r(m_plan, buffer, buffer); }

 private:
  fftwf_plan m_plan = nullptr;
};

}  // namespace

void dct_solve(int width, int height, const float* rhs, float* x, double c, double s, int threads) {
  DP_CHECK(width > 0 && height > 0, "dct_solve: empty image");
  DP_CHECK(c >= 0.0 && s > 0.0, "dct_solve: needs c >= 0 and s > 0");
  const size_t n = size_t(width) * size_t(height);
  FftwBuffer planes[3];
  for (auto& p : planes) {
    p.reset(static_cast<float*>(fftwf_malloc(sizeof(float) * n)));
    DP_CHECK(p != nullptr, "dct_solve: out of memory");
  }
  const Plan forward(width, height, planes[0].get(), FFTW_REDFT10);
  const Plan inverse(width, height, planes[0].get(), FFTW_REDFT01);

  // Eigenvalues of c H^T H + s per axis (Bhat 2008): c (2 - 2 cos(pi u / W)) + ...
  // FFTW's REDFT01(REDFT10(x)) = 2W * 2H * x: the normalization is folded in.
  std::vector<double> ex(static_cast<size_t>(width)), ey(static_cast<size_t>(height));
  for (int u = 0; u < width; ++u) ex[size_t(u)] = c * (2.0 - 2.0 * std::cos(kPiD * u / width));
  for (int v = 0; v < height; ++v) ey[size_t(v)] = c * (2.0 - 2.0 * std::cos(kPiD * v / height));
  const double norm = 1.0 / (4.0 * double(width) * double(height));

  threads = std::min(resolve_threads(threads), 3);
  run_team(threads, [&](int t) {
    for (int ch = t; ch < 3; ch += threads) {
      float* buf = planes[ch].get();
      for (size_t i = 0; i < n; ++i) buf[i] = rhs[3 * i + size_t(ch)];
      forward.run(buf);
      for (int v = 0; v < height; ++v) {
        float* line = buf + size_t(v) * size_t(width);
        for (int u = 0; u < width; ++u)
          line[u] = float(double(line[u]) * norm / (s + ex[size_t(u)] + ey[size_t(v)]));
      }
      inverse.run(buf);
    }
  });
  // Written after every channel is read: rhs and x may alias.
  for (int ch = 0; ch < 3; ++ch) {
    const float* buf = planes[ch].get();
    for (size_t i = 0; i < n; ++i) x[3 * i + size_t(ch)] = buf[i];
  }
}

}  // namespace dp::reconstruct
