// Start states and the normalisation of path-space chains (Veach 1997, Sec. 11.3.1-2; as
// Mitsuba 0.6's path sampler, docs/memlt_plan.md Sec. 4): n independent BDPT samples
// (one camera subpath through a raster uniform on the whole image, one light subpath,
// every strategy (s, t) with power-heuristic MIS) give
//   b = mean over samples of sum_st lum(w_st C_st) = integral of lum F (the mean pixel
//       luminance in McmcDriver's units: pixel = b W H / mutations * splats),
// and a start path is the (s, t) path of one sample chosen with probability proportional
// to lum(w_st C_st) (strategies of depth min_depth .. max_depth only). Its density is sum_st p_st w_st lum C_st / b' = lum F / b' whatever
// the MIS weights (sampling-importance-resampling: no burn-in). Sample i uses its own
// random stream (seed, i), so b and every start depend on the seed only, not on the
// thread count, and a chosen sample is rebuilt by re-running its stream.
#pragma once

#include <cstdint>
#include <vector>

#include "mcmc/path_state.h"
#include "mcmc/sample_share.h"

namespace dp::mcmc {

struct PathSeedOptions {
  int max_depth = 8;  // paths of at most this many segments
  int min_depth = 1;  // and at least this many (3: direct light rendered separately)
  int rr_depth = 5;   // BDPT's Russian roulette (unbiased: b and the start law are unaffected)
  int64_t samples = 100000;
  uint64_t seed = 0;
  int threads = 1;
};

class PathSeeder {
 public:
  PathSeeder(const scene::Scene& scene, const PathSeedOptions& options);
  double b() const { return m_b; }
  int64_t samples() const { return int64_t(m_sum.size()); }
  int64_t invalid() const { return m_invalid; }  // samples with a non-finite value (dropped)
  // The samples of part `part` of `parts` (sample_share.h, blocks of kBlock), in index
  // order: share(0, 1) is every sample, its sum / n is b() exactly.
  SampleShare share(int part, int parts) const;
  static constexpr int64_t kBlock = 256;
  // The start path for u in [0, 1): a sample chosen with probability proportional to its
  // summed lum(w C), then one of its strategies with probability proportional to its
  // own (the residual of u). False if every sample is zero or the path does not evaluate.
  bool select(double u, PathState& out, PathSides& sides) const;

 private:
  const scene::Scene& m_scene;
  PathSeedOptions m_opt;
  std::vector<double> m_sum, m_cdf;  // per sample: sum_st lum(w_st C_st), and its running sum
  std::vector<char> m_bad;           // per sample: non-finite (dropped)
  double m_b = 0;
  int64_t m_invalid = 0;
};

}  // namespace dp::mcmc
