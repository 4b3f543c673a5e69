#include "core/metrics.h"

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace dp::core {

namespace {
// Per-pixel errors (already averaged over channels), non-finite pixels skipped.
template <typename F>
double mean_error(const Image& x, const Image& ref, size_t discard, F per_channel, size_t* nonfinite = nullptr) {
  DP_CHECK(x.same_size(ref), "metric: image sizes differ");
  std::vector<double> e;
  e.reserve(x.size());
  size_t bad = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!is_finite(x[i])) {
      ++bad;
      continue;
    }
    double s = 0;
    for (int c = 0; c < 3; ++c) s += per_channel(double(x[i][c]), double(ref[i][c]));
    e.push_back(s / 3.0);
  }
  if (nonfinite) *nonfinite = bad;
  if (discard > 0 && discard < e.size()) {
    std::nth_element(e.begin(), e.end() - std::ptrdiff_t(discard), e.end());
    e.resize(e.size() - discard);
  }
  double sum = 0;
  for (double v : e) sum += v;
  return e.empty() ? 0.0 : sum / double(e.size());
}
}  // namespace

double mse(const Image& x, const Image& ref, size_t discard) {
  return mean_error(x, ref, discard, [](double a, double r) { return (a - r) * (a - r); });
}

double relmse(const Image& x, const Image& ref, size_t discard, double eps) {
  return mean_error(x, ref, discard, [eps](double a, double r) { return (a - r) * (a - r) / (r * r + eps); });
}

ErrorReport compare(const Image& x, const Image& ref, size_t discard) {
  ErrorReport r;
  r.mse = mean_error(x, ref, discard, [](double a, double b) { return (a - b) * (a - b); }, &r.nonfinite);
  r.relmse = relmse(x, ref, discard);
  r.mape = mean_error(x, ref, discard, [](double a, double b) { return std::abs(a - b) / (std::abs(b) + 1e-2); });
  Image xf = x;
  xf.zero_nonfinite();
  r.mean_image = xf.mean();
  r.mean_reference = ref.mean();
  for (int c = 0; c < 3; ++c)
    r.mean_ratio[c] = r.mean_reference[c] != 0 ? r.mean_image[c] / r.mean_reference[c] : 0.0;
  return r;
}

}  // namespace dp::core
