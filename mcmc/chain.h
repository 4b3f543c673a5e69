// One Metropolis-Hastings chain over primary sample space (Kelemen et al. 2002):
// the state x is the coordinate vector recorded by a pathspace::PrimarySampleStream.
// Each step proposes y by a large step (probability large_step_prob) or a small step
// (kernel.h), evaluates f(y) with the Target, and accepts with
// a = acceptance(f(x), f(y)) = min(1, f(y) / f(x)) (Veach 1997, Eq. 11.4, symmetric
// kernels: the proposal densities cancel). A zero, negative or non-finite f(y) is
// rejected (a = 0); non-finite ones are counted.
// Lazy coordinates: a state is conceptually an infinite vector of which only the
// coordinates read so far are stored. When the proposal reads past the stored part of
// x, the stream draws y's new values uniformly. This is exact: f(x) does not depend on
// the coordinates x has not read, so their conditional law under the target is uniform,
// and drawing them afresh before each proposal is a Gibbs refresh that leaves the target
// invariant (pbrt-v3's MLTSampler instead keeps a lazily created value of x and perturbs
// it; both are valid). Stored coordinates that the current path does not read are kept
// and mutated with the others.
#pragma once

#include <cstdint>

#include "mcmc/kernel.h"
#include "mcmc/target.h"

namespace dp::mcmc {

// Acceptance probability of moving from f(x) to f(y).
using AcceptanceRule = double (*)(double fx, double fy);
// min(1, f(y) / f(x)); 0 if f(y) is not positive and finite; 1 if f(x) == 0 < f(y).
double metropolis_acceptance(double fx, double fy);

// Applies one small step to every coordinate of u. The chain's acceptance assumes the
// step is symmetric (K(x -> y) = K(y -> x)).
using SmallStep = void (*)(const KelemenKernel& kernel, std::vector<float>& u, core::Rng& rng);
void kelemen_small_step(const KelemenKernel& kernel, std::vector<float>& u, core::Rng& rng);

struct ChainOptions {
  double large_step_prob = 0.3;  // Mitsuba PSSMLT default
  KelemenKernel kernel;
  // Both replaced only by tests, which must detect a wrong rule or an asymmetric step.
  AcceptanceRule acceptance = metropolis_acceptance;
  SmallStep small_step = kelemen_small_step;
  // The first `redraw_first` coordinates are drawn afresh (uniformly) by every small step
  // too: an independent uniform proposal of those coordinates, symmetric like the rest
  // (GD-MLT's neighbour choice, Manzi et al. 2014, Sec. 4).
  int redraw_first = 0;
};

struct ChainCounters {
  int64_t large = 0, small = 0;                    // proposals by kind
  int64_t accepted_large = 0, accepted_small = 0;  // accepted proposals by kind
  int64_t invalid = 0;                             // non-finite proposals (rejected, never splatted)
  int64_t zero = 0;                                // proposals with f(y) == 0 (rejected)
  void merge(const ChainCounters& o);
  double acceptance_rate() const;
};

// What one step looked at: the state before the step, the proposal and a. Expected-value
// splatting (Veach 1997, Sec. 11.3.3): x with weight 1 - a, y with weight a.
struct Step {
  TargetValue current, proposed;
  double a = 0;
  bool large = false, accepted = false;
};

class Chain {
 public:
  // `seed` and `index` select the chain's random stream deterministically.
  Chain(Target& target, const ChainOptions& options, uint64_t seed, uint64_t index);
  // Starts at the state with coordinates `u` (missing coordinates are drawn uniformly).
  void start(const std::vector<float>& u);
  Step step();

  const TargetValue& current() const { return m_value; }
  const std::vector<float>& state() const { return m_x; }
  const ChainCounters& counters() const { return m_counters; }

 private:
  Target& m_target;
  ChainOptions m_opt;
  core::Rng m_rng;
  // No member refers to another member (a PrimarySampleStream bound to m_rng would
  // dangle after a move): step() builds its stream on the stack around m_y, so a Chain
  // is safe to move and copy (std::vector<Chain> may reallocate).
  std::vector<float> m_y;  // the proposal y (kept to reuse its allocation)
  std::vector<float> m_x;  // the current state x
  TargetValue m_value;                      // f(x) and its splat
  ChainCounters m_counters;
};

}  // namespace dp::mcmc
