// Chi-square goodness-of-fit harness for direction samplers (BSDFs, emitters, phase
// functions, warps). The sphere is binned in (cos theta, phi); expected counts come
// from integrating the claimed pdf over each cell (adaptive Simpson on a sub-grid);
// cells with expected count < 5 are pooled; the p-value uses the chi-square CDF
// (boost::math). Significance is Šidák-corrected for the number of tests run.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/math.h"
#include "core/rng.h"

namespace dp::test {

struct Chi2Options {
  int theta_bins = 10;  // bins in cos(theta) over [-1, 1]
  int phi_bins = 20;
  int samples = 200000;
  double significance = 0.01;  // family-wise level before Šidák correction
  int test_count = 1;          // number of tests in the family (Šidák)
  uint64_t seed = 1;
};

struct Chi2Result {
  bool passed = false;
  double p_value = 0;
  double statistic = 0;
  int dof = 0;
  double integral = 0;        // integral of the pdf over the sphere (<= 1)
  double sampled_fraction = 0;  // fraction of sample() calls that returned a direction
  std::string report;         // observed vs expected table (printed on failure)
};

// `sample` returns a unit direction or nullopt (absorbed / delta lobe, excluded from
// the histogram but counted in the total). `pdf` is the solid-angle density of the
// non-delta part at a direction.
using DirectionSampler = std::function<std::optional<Vec3>(core::Rng&)>;
using DirectionPdf = std::function<double(const Vec3&)>;

Chi2Result chi2_sphere(const DirectionSampler& sample, const DirectionPdf& pdf, const Chi2Options& opt = {});

// Integral of pdf over the sphere (checks normalization separately from the fit).
double integrate_sphere(const DirectionPdf& pdf, int theta_res = 256, int phi_res = 512);

}  // namespace dp::test
