// One Metropolis-Hastings chain over path space (Veach 1997, Ch. 11): the state is a full
// path (path_state.h); each step picks one of the mutations suitable for the current path
// with probability s_x = w_i / sum of the suitable w_j (Mitsuba 0.6's selection), proposes
// y with it and accepts with
//   a = min(1, ratio(x, y) * s_y / s_x)   (mutator.h; s_y on y's own suitable set).
// A failed proposal is a rejection (the current path keeps its weight) and is counted by
// mutation and cause. Expected-value splatting (Veach 1997, Sec. 11.3.3) is the caller's:
// the step reports the current path and the proposal with a. The chain owns all its
// memory and no member refers to another, so chains can live in a std::vector.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "mcmc/mutator.h"

namespace dp::mcmc {

struct MutatorCounters {
  int64_t proposed = 0, accepted = 0;
  std::array<int64_t, size_t(ProposalStatus::count)> status{};  // proposals by outcome
  double acceptance_sum = 0;                                     // sum of a over the proposals
  // By the current path's depth (segments; the last entry also counts deeper paths).
  static constexpr int kDepths = 16;
  std::array<int64_t, kDepths> proposed_by_depth{}, accepted_by_depth{};
  void merge(const MutatorCounters& o);
};

struct PathChainCounters {
  std::vector<MutatorCounters> mutators;  // in the order of the chain's mutators
  int64_t invalid = 0;                    // proposals whose acceptance was not finite (rejected)
  int64_t stuck = 0;                      // steps at a path no mutation applies to
  void merge(const PathChainCounters& o);
};

// One state as splatted: F / lum F (luminance 1) at a raster position; on an extended
// target also the state's factor and pair sample (path_state.h: the caller divides both
// colour and pair by the factor).
struct PathSplat {
  Rgb colour = Rgb::Zero();
  Vec2 raster{0, 0};
  double factor = 1;
  Rgb pair = Rgb::Zero();
  int64_t pair_row = -1;
  static PathSplat of(const PathState& s) { return {s.colour(), s.raster, s.factor, s.pair, s.pair_row}; }
};

// An extended target over (path, u_pair): f = lum F(x) * factor(x, u_pair) (e.g. GD-MLT's,
// path_gradient.h). u_pair is uniform on [0, 1) and redrawn independently at every
// proposal, a symmetric move of that coordinate, so the acceptance only gains the factor
// ratio. evaluate() sets factor (>= 0; NaN marks an invalid state), pair and pair_row.
// One per chain (it may keep scratch memory).
class PathTargetFactor {
 public:
  virtual ~PathTargetFactor() = default;
  virtual void evaluate(PathState& s) = 0;
};

struct PathStep {
  PathSplat current, proposed;
  double a = 0;  // 0 when no proposal was made
  bool accepted = false;
  int mutator = -1;  // the mutation tried (index into the chain's list; -1: none applied)
  ProposalStatus status = ProposalStatus::ok;
};

struct WeightedMutator {
  const Mutator* mutator = nullptr;
  double weight = 1;
};

class PathChain {
 public:
  // `factor`: the extended target's (nullptr: the primal target lum F); owned by the chain.
  PathChain(std::vector<WeightedMutator> mutators, uint64_t seed, uint64_t index,
            std::unique_ptr<PathTargetFactor> factor = nullptr);
  // x must carry its factor already when the chain has one (the seeding resamples by it).
  void start(const PathState& x);
  PathStep step();
  const PathState& current() const { return m_x; }
  const PathChainCounters& counters() const { return m_counters; }
  const PathTargetFactor* factor() const { return m_factor.get(); }

 private:
  // Selection probability of mutator i on s (0 if it does not apply).
  double selection(const PathState& s, size_t i) const;

  std::vector<WeightedMutator> m_mutators;
  std::unique_ptr<PathTargetFactor> m_factor;
  core::Rng m_rng;
  PathState m_x, m_y;
  PathSides m_sides;
  PathChainCounters m_counters;
};

}  // namespace dp::mcmc
