// What the path-space Markov chains of `mlt mutations=path`, `memlt` and `gdmlt
// mutations=path` share: the mutation settings (one set of keys and defaults), the
// mutators built from them, a chain's start path, and the per-mutation JSON counters.
#pragma once

#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "mcmc/mut_bidir.h"
#include "mcmc/mut_caustic.h"
#include "mcmc/mut_lens.h"
#include "mcmc/mut_manifold.h"
#include "mcmc/mut_multichain.h"
#include "mcmc/path_chain.h"
#include "mcmc/path_seed.h"

namespace dp::integrators {

struct PathMutationSettings {
  std::string preset = "veach";  // the default of `mutators` (memlt and gdmlt: "memlt")
  std::vector<std::string> mutators{"bidir", "lens", "caustic", "multichain"};
  double manifold_lambda = 50;       // vMF peak factor of the manifold perturbation
  double manifold_sensor_prob = 0.25;
  // Reads `mutators`, `manifold_lambda`, `manifold_sensor_prob` (defaults: this object's,
  // `mutators` from `preset`); dp::ValueError names the key.
  void read(Settings& s);
};

// The mutators of a chain set (shared read-only by all chains), in settings order,
// each with selection weight 1 (Mitsuba 0.6's default).
class PathMutatorSet {
 public:
  // Bidirectional mutation lengths: paths of min_depth .. max_depth segments.
  PathMutatorSet(const scene::Scene& scene, const PathMutationSettings& settings, int min_depth, int max_depth,
                 mcmc::BidirMutationFault fault = mcmc::BidirMutationFault::none);
  const std::vector<mcmc::WeightedMutator>& list() const { return m_list; }

 private:
  mcmc::BidirMutation m_bidir;
  mcmc::LensPerturbation m_lens;
  mcmc::CausticPerturbation m_caustic;
  mcmc::MultiChainPerturbation m_multichain;
  mcmc::ManifoldPerturbation m_manifold;
  std::vector<mcmc::WeightedMutator> m_list;
};

// The seeder's options for a render (threads and seed from `options`; paths of
// min_depth .. options.max_depth segments).
mcmc::PathSeedOptions seed_options(const RenderOptions& options, int rr_depth, int64_t bootstrap, int min_depth);

// The start path of chain c: a seeder path chosen with probability proportional to
// lum(w C) (path_seed.h); returns the retries needed (dp::Error after 100).
int start_path(const mcmc::PathSeeder& seeder, uint64_t seed, int c, const std::string& name, mcmc::PathState& x);

// `<name>.path.<mutation>.proposed/accepted/fail.<cause>`, stuck, invalid, and the
// acceptance per mutation (info); returns the proposals that were not finite.
int64_t report_path_chains(RenderResult& result, const std::string& name,
                           const std::vector<mcmc::WeightedMutator>& mutators, const mcmc::PathChainCounters& sum);

}  // namespace dp::integrators
