// The contract of a path-space mutation (Veach 1997, Sec. 11.4; Mitsuba 0.6's Mutator,
// docs/memlt_plan.md Sec. 1): whether it applies to a path, a proposal y with the record
// of what changed, and the ratio that makes the chain's acceptance
//   a(x -> y) = min(1, ratio(x, y, rec) * s_y / s_x),
//   ratio = [F(y) T(y -> x)] / [F(x) T(x -> y)],
// with s the mutator's normalised selection probability on each path (the suitable set
// may differ between x and y). Each mutation forms the ratio from the states' C_s = F/p_s
// (path_state.h) and its own densities, so factors common to x and y cancel exactly.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "mcmc/bidir_choice.h"
#include "mcmc/path_state.h"

namespace dp::mcmc {

// Why a proposal was not made (each counted; a failed proposal is a rejected step).
enum class ProposalStatus : uint8_t {
  ok,
  no_choice,         // bidirectional: no admissible (k', kd, l, s) on x
  walk_ended,        // a walk or a re-traced chain ended early (miss, no material, sidedness)
  light_not_found,   // bidirectional, s = 0 from the light supernode: the camera walk missed the lights
  escaped,           // a camera walk escaped to the environment before its last vertex
  occluded,          // the connection edge is blocked
  zero,              // the proposal contributes nothing (or nothing finite)
  off_image,         // lens: the perturbed raster position left the image
  configuration,     // a perturbation changed the path's configuration (a Dirac lobe lost, a smooth vertex became Dirac)
  chain_walk,        // manifold: the specular chain's walk failed or was not reversible
  nonfinite,         // the proposal's value is NaN or infinite (dropped and counted)
  count
};
const char* proposal_status_name(ProposalStatus s);

// What a mutation changed (read back by its ratio()).
struct MutationRecord {
  BidirChoice bidir;  // bidirectional mutation: the discrete choice
  int l = 0;          // perturbations: the kept vertex the re-traced part starts after / ends at
  double theta = 0;   // caustic: the angle between the old and the new direction at x_l
  // manifold: the perturbed vertex a, the re-traced end b, the pinned end c, the direction
  // (+1 toward the camera), the strategy whose densities the ratio uses, the cosine of the
  // angle between the old and new direction at a, and the walked chain's Jacobian ratio
  // [G(y_b, c)/|cos y_b|] / [G(x_b, c)/|cos x_b|] (1 without a chain).
  int a = 0, b = 0, c = 0, step = 0, strategy = 0;
  double cos_turn = 1, jacobian = 1;
  // The record of the move from the proposal back to the source.
  MutationRecord reverse() const {
    MutationRecord r = *this;
    r.bidir = bidir.reverse();
    r.jacobian = 1.0 / jacobian;
    return r;
  }
};

class Mutator {
 public:
  virtual ~Mutator() = default;
  virtual const char* name() const = 0;
  virtual bool suitable(const PathState& x) const = 0;
  // Proposes y from a suitable x (x unchanged; `sides` is scratch).
  virtual ProposalStatus sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                PathSides& sides) const = 0;
  // [F(y) T(y -> x)] / [F(x) T(x -> y)] of the move rec (0 if its reverse is impossible).
  virtual double ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const = 0;
};

}  // namespace dp::mcmc
