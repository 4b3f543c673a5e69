// `deltapath stress`: renders every stress scene family (stress_scenes.h) with every
// registered integrator at default settings and reports, per (family, integrator):
//   - samples dropped as NaN/Inf (sum of the counters named "*nan_dropped"),
//   - non-finite pixels in any output layer (must be zero: a dropped sample is fine,
//     a non-finite value in an image buffer is a bug),
//   - failure and outlier counters by cause (counters whose name contains "fail",
//     "jacobian", "outlier", "diverged" or "not_invertible"),
//   - the largest finite pixel value over all layers and counters containing "max".
// Quick mode (CI): two variants per family at 32x32, 4 spp, and the photon-beam/-plane
// estimators at 2 000 light paths per iteration. Full: 4 variants, 64x64, 16 spp, defaults.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dp::experiments {

struct StressOptions {
  bool quick = false;
  uint64_t seed = 1;
  int threads = 0;
  std::vector<std::string> integrators;  // empty = every registered integrator
  int variants = 0;                      // 0 = mode default
  std::string image_dir;                 // if set: <family>-<variant>-<integrator>.png per render
};

struct StressCase {
  std::string family, integrator;
  int renders = 0;
  int64_t samples_dropped = 0;      // "*nan_dropped" counters
  uint64_t nonfinite_pixels = 0;    // in any layer of any render
  std::string nonfinite_layers;     // names of the layers that had them
  double max_value = 0;             // largest finite channel value over all layers
  std::string max_layer;
  std::map<std::string, int64_t> failures;  // failure/outlier counters (non-zero only)
  std::map<std::string, int64_t> maxima;    // counters containing "max" (max over renders)
  double seconds = 0;
  std::string skipped;  // why the integrator was not run on this family (renders = 0), e.g. no media support
};

struct StressReport {
  std::vector<StressCase> cases;
  uint64_t nonfinite_pixels() const;
  int64_t samples_dropped() const;
};

StressReport run_stress(const StressOptions& options);
// Fixed-width table plus the failure counters, for stdout.
std::string format_stress_report(const StressReport& report);
// CSV: family,integrator,renders,samples_dropped,nonfinite_pixels,max_value,max_layer,seconds
std::string stress_csv(const StressReport& report);

}  // namespace dp::experiments
