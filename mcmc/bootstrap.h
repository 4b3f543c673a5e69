// Bootstrap normalisation of primary-sample-space MLT (Kelemen et al. 2002, Sec. 4;
// Veach 1997, Sec. 11.3.1): b = E[f(u)] over uniform primary samples u, estimated from
// n independent samples. The chain samples u with density f / b, so an unbiased pixel
// estimate is b * E_{f/b}[h_j C / f]. The samples are also the pool from which chains
// start: choosing sample i with probability f_i / sum f gives a start state distributed
// (approximately, for large n) as f / b, so no burn-in is needed (Veach 1997, Sec. 11.3.2).
// Sample i is evaluated with the random stream of its block of kBlock samples, so b
// depends only on the seed (not on the thread count) and any sample can be replayed.
#pragma once

#include <cstdint>
#include <vector>

#include "mcmc/sample_share.h"
#include "mcmc/target.h"

namespace dp::mcmc {

class Bootstrap {
 public:
  static constexpr int64_t kBlock = 256;

  // Evaluates n samples on `threads` threads (one Target per block from `make`).
  Bootstrap(const TargetFactory& make, int64_t n, uint64_t seed, int threads);

  double b() const { return m_b; }           // mean f (invalid samples count as 0)
  int64_t samples() const { return int64_t(m_f.size()); }
  int64_t invalid() const { return m_invalid; }  // non-finite samples (dropped)
  // The samples of part `part` of `parts` (sample_share.h; blocks of kBlock), summed in
  // index order: share(0, 1) is every sample, its sum / n is b() exactly.
  SampleShare share(int part, int parts) const;
  // Index of the sample chosen with probability f_i / sum f for u in [0, 1); -1 if all f are 0.
  int64_t select(double u) const;
  // The primary sample coordinates of sample i (re-evaluated with `target`).
  std::vector<float> replay(Target& target, int64_t i) const;

 private:
  uint64_t m_seed;
  std::vector<double> m_f, m_cdf;
  std::vector<char> m_bad;  // per sample: non-finite (dropped)
  double m_b = 0;
  int64_t m_invalid = 0;
};

}  // namespace dp::mcmc
