// Round-based scheduling of independent Markov chains, shared by the MCMC integrators
// (`mlt`, `gdmlt`). A render runs rounds; in each round every chain runs up to `round`
// mutations (its remaining quota in --spp mode) and records its splats in its own list;
// after the round the lists are added to the image buffers in chain order. So:
//  * the image depends on the seed and the chain count only, not on the thread count or
//    on which thread ran which chain (sums are formed in one fixed order);
//  * memory is one splat list per chain of about one round's splats, not one image per
//    chain or per thread;
//  * an interrupted render (Ctrl-C, or the --time budget) has run whole rounds on most
//    chains: the whole image at fewer mutations, never a black region.
// The caller owns the chains; `step` runs n mutations of chain c into `out`.
// Shares (`render --part K/N`, `--mpi`; issue 17): part k of n runs only the chains
// c with c % n == k, each with its whole-render quota, round size and stream, so the
// chains of the n parts make exactly the splats of the single render (their sums are
// formed in another order: equal up to double rounding).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math.h"
#include "integrators/integrator.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

// Splats of one chain in one round, in the order they were made.
struct SplatList {
  struct Splat {
    int32_t layer, pixel;
    Rgbd value;
  };
  std::vector<Splat> splats;
  void add(int layer, int64_t pixel, const Rgbd& v) { splats.push_back({int32_t(layer), int32_t(pixel), v}); }
};

struct ChainSchedule {
  int chains = 1;
  int64_t total = 0;  // mutations in all (--spp mode); ignored when the options are timed
  int64_t round = 1;  // mutations per chain per round
  int layers = 1;     // accumulation buffers, each `pixels` long
  int64_t pixels = 0;
  int part = 0, parts = 1;  // run only chains c with c % parts == part
  // Optional: called on the calling thread after each round (with the rounds so far).
  std::function<void(int64_t rounds)> after_round;
};

struct ChainRunResult {
  std::vector<std::vector<Rgbd>> sums;  // [layer][pixel]
  std::vector<int64_t> mutations;      // per chain
  int64_t total_mutations = 0;
  int64_t rounds = 0;
  bool interrupted = false;  // options.stop was set
  bool partial = false;      // interrupted, or fewer mutations than this part's quotas in --spp mode
  double seconds = 0;
};

using ChainStep = std::function<void(int chain, int64_t n, SplatList& out, int thread)>;

// The chain count of a `chains` setting: the setting when > 0, else 4 per thread -- but
// for a render split into parts 16 per part, so that parts on machines with different
// thread counts still share one chain set (each chain owned by one part, the quotas of
// the single render of that chain set).
inline int resolve_chains(int setting, const RenderOptions& options) {
  if (setting > 0) return setting;
  return options.parts > 1 ? 16 * options.parts : 4 * resolve_threads(options);
}
// Whether chain c is one of this part's (ChainSchedule::part/parts).
inline bool owns_chain(int c, int part, int parts) { return parts <= 1 || c % parts == part; }
inline bool owns_chain(const ChainSchedule& sc, int c) { return owns_chain(c, sc.part, sc.parts); }
// Mutations chain c runs in --spp mode (total / chains, the first total % chains one more).
inline int64_t chain_quota(const ChainSchedule& sc, int c) {
  return sc.total / sc.chains + (c < sc.total % sc.chains ? 1 : 0);
}
// Rounds a complete --spp render of all the chains takes (whatever the part).
int64_t whole_rounds(const ChainSchedule& sc);

ChainRunResult run_chains(const ChainSchedule& schedule, const RenderOptions& options, const std::string& label,
                          const ChainStep& step);

}  // namespace dp::integrators
