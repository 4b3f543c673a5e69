// One Metropolis-Hastings chain over path space (Veach 1997, Ch. 11): the state is a full
// path (path_state.h), each step proposes y with the bidirectional mutation
// (mut_bidir.h) and accepts it with a(x -> y) = min(1, F(y) T(y -> x) / (F(x) T(x -> y))).
// A failed proposal is a rejection (the current path keeps its weight) and is counted by
// cause. Expected-value splatting (Veach 1997, Sec. 11.3.3) is the caller's: the step
// reports the current path and the proposal with a. The chain owns all its memory, and no
// member refers to another, so chains can live in a std::vector.
#pragma once

#include <array>
#include <cstdint>

#include "mcmc/mut_bidir.h"

namespace dp::mcmc {

struct PathChainCounters {
  int64_t proposed = 0, accepted = 0;
  std::array<int64_t, size_t(ProposalStatus::count)> status{};  // proposals by outcome
  int64_t invalid = 0;  // proposals whose acceptance was not finite (rejected)
  void merge(const PathChainCounters& o);
};

// One state as splatted: F / lum F (luminance 1) at a raster position.
struct PathSplat {
  Rgb colour = Rgb::Zero();
  Vec2 raster{0, 0};
};

struct PathStep {
  PathSplat current, proposed;
  double a = 0;  // 0 when no proposal was made
  bool accepted = false;
};

class PathChain {
 public:
  PathChain(const BidirMutation& mutation, uint64_t seed, uint64_t index);
  void start(const PathState& x);
  PathStep step();
  const PathState& current() const { return m_x; }
  const PathChainCounters& counters() const { return m_counters; }

 private:
  const BidirMutation* m_mutation;
  core::Rng m_rng;
  PathState m_x, m_y;
  PathSides m_sides;
  PathChainCounters m_counters;
};

}  // namespace dp::mcmc
