// Veach's bidirectional mutation (Veach 1997, Sec. 11.4.2) in Mitsuba 0.6's form
// (docs/memlt_plan.md, Sec. 2.1): delete the vertices between two kept vertices l and m
// of the current path x (extended indices, bidir_choice.h), walk s new vertices from l
// toward the camera (importance mode) and ka - 1 - s from m toward the light (radiance
// mode), both without Russian roulette, and connect the two walks' ends. The proposal y
// is literally BDPT strategy (l + s, ...) of itself, so its density is
//   T(x -> y) = pmf(k', kd, l, s on x) * sum_{s' in x's split range} p_{l+s'}(y) / p_kept,
// the sum over every split that could have produced y (the split is not part of the
// state), with p_kept the density of the kept vertices (identical in x and y: it cancels).
// With C_s = F / p_s (path_state.h):
//   T(x -> y) / F(y) = pmf(rec on x) * sum_{s'} 1 / lum C_{l+s'}(y) / p_kept,
// and the Metropolis-Hastings ratio is
//   a(x -> y) = min(1, [T(y -> x) / F(x)] / [T(x -> y) / F(y)]),
// with the reverse move rec.reverse() evaluated on y (its own admissible left ends and
// split range). Dirac lobes need no special case: every C_s is a ratio of finite
// numbers (the lobe's sample weight).
#pragma once

#include <cstdint>

#include "mcmc/mutator.h"

namespace dp::mcmc {

// Deliberate defects the tests must reject (tests/mcmc/test_mut_bidir.cpp); none in renders.
enum class BidirMutationFault : uint8_t {
  none,
  sampled_split_only,  // T sums only the split that was sampled (misses the others)
  pmf_from_source,     // the reverse move's pmf is evaluated on x instead of y
};

class BidirMutation final : public Mutator {
 public:
  BidirMutation(const scene::Scene& scene, const BidirLengths& lengths,
                BidirMutationFault fault = BidirMutationFault::none);
  const char* name() const override { return "bidir"; }
  bool suitable(const PathState&) const override { return true; }  // the only mutation that changes lengths
  ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                        PathSides& sides) const override;
  double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const override;

  // The extended-index shape of x: which vertices can bound a mutation.
  BidirShape shape(const PathState& x) const;
  // Proposes y from x (x unchanged). `rec` is the move, for inverse_weight().
  ProposalStatus sample_choice(const PathState& x, PathState& y, BidirChoice& rec, core::Rng& rng,
                               PathSides& sides) const;
  // T(src -> dst) / F(dst) * p_kept for the move `rec` made on src (0 if the move cannot be made).
  double inverse_weight(const PathState& src, const PathState& dst, const BidirChoice& rec) const;

 private:
  // The same with the pmf taken on `pmf_shape` and the split range on `range_shape`
  // (both the source's, except in a fault).
  double inverse_weight(const BidirShape& pmf_shape, const BidirShape& range_shape, const PathState& dst,
                        const BidirChoice& rec) const;

  const scene::Scene& m_scene;
  BidirLengths m_lengths;
  BidirMutationFault m_fault;
  bool m_light_hittable = true;
};

}  // namespace dp::mcmc
