// Settings of primary-sample-space MLT (`--integrator mlt`). Each key is read with its
// default and documentation in mlt_settings.cpp and written to the sidecar.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/path_chains.h"
#include "integrators/settings.h"
#include "mcmc/chain.h"
#include "mcmc/mut_bidir.h"
#include "mcmc/mut_caustic.h"

namespace dp::integrators {

struct MltSettings {
  double large_step_prob = 0.3;  // probability of a large step (Mitsuba PSSMLT default)
  int64_t bootstrap = 100000;    // independent samples estimating the normalisation b
  bool large_step_b = true;      // refine b with the large steps' f (independent uniform samples)
  int chains = 0;                // independent chains; 0 = 4 per thread
  int rr_depth = 5;              // Russian roulette after this many segments (as PT)
  bool nee = true;               // next-event estimation with MIS inside each path (as PT)
  // Path-space chains (docs/memlt_plan.md): mutations=path and the mutation set.
  bool path_space = false;
  PathMutationSettings path_mutations;  // memlt: preset "memlt"
  // Path space: direct light (<= 2 segments) by PT; 0 = auto (interleaved with the chains'
  // rounds, as many samples per pixel as mutations per pixel), -1 = by the chains.
  int direct_spp = 0;
  int replay_chain = -1;        // replay=CHAIN:STEP: re-run chain CHAIN to step STEP, write its state
  int64_t replay_step = 0;
  // Not a --set key: a deliberate defect of the bidirectional mutation (tests).
  mcmc::BidirMutationFault path_fault = mcmc::BidirMutationFault::none;
  // Not a --set key: tests replace it by an asymmetric step the render must be rejected for.
  mcmc::SmallStep small_step = mcmc::kelemen_small_step;

  // `defaults`: the integrator's own defaults (memlt: path space with the memlt set).
  static MltSettings read(Settings& s);
  static MltSettings read(Settings& s, const MltSettings& defaults);
};

}  // namespace dp::integrators
