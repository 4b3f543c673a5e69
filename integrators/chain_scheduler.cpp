#include "integrators/chain_scheduler.h"

#include <algorithm>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

int64_t whole_rounds(const ChainSchedule& sc) {
  if (sc.chains <= 0 || sc.total <= 0) return 0;
  const int64_t most = chain_quota(sc, 0);  // chain 0 has the largest quota
  return (most + sc.round - 1) / sc.round;
}

ChainRunResult run_chains(const ChainSchedule& sc, const RenderOptions& options, const std::string& label,
                          const ChainStep& step) {
  core::Timer timer;
  ChainRunResult r;
  r.sums.assign(size_t(sc.layers), std::vector<Rgbd>(size_t(sc.pixels), Rgbd::Zero()));
  r.mutations.assign(size_t(sc.chains), 0);
  const bool timed = options.time_budget > 0;
  std::vector<int64_t> quota(size_t(sc.chains), 0);
  int64_t own_total = 0;  // this part's mutations in --spp mode
  for (int c = 0; c < sc.chains; ++c)
    if (owns_chain(sc, c)) own_total += quota[size_t(c)] = chain_quota(sc, c);
  const int threads = std::min(resolve_threads(options), std::max(1, sc.chains));
  std::vector<SplatList> lists(size_t(sc.chains));

  core::Progress progress(label, timed ? 1000 : std::max<int64_t>(1, own_total), options.quiet);
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (options.stop && options.stop->load()) return true;
    return timed && timer.seconds() >= options.time_budget;
  };
  bool any = false;  // this part has a chain
  for (int c = 0; c < sc.chains; ++c) any |= owns_chain(sc, c);
  for (bool busy = any; busy && !should_stop();) {
    core::parallel_for(
        sc.chains, threads,
        [&](int64_t c, int thread) {
          if (should_stop()) {
            stop.store(true);
            return;
          }
          if (!owns_chain(sc, int(c))) return;
          const int64_t n = timed ? sc.round : std::min(sc.round, quota[size_t(c)]);
          if (n <= 0) return;
          lists[size_t(c)].splats.clear();
          step(int(c), n, lists[size_t(c)], thread);
          r.mutations[size_t(c)] += n;
          if (timed) progress.set_fraction(timer.seconds() / options.time_budget);
          else progress.advance(n);
        },
        &stop);
    // Merge in chain order (deterministic sums); a chain that did not run this round
    // has an empty list.
    busy = false;
    for (int c = 0; c < sc.chains; ++c) {
      for (const auto& s : lists[size_t(c)].splats) r.sums[size_t(s.layer)][size_t(s.pixel)] += s.value;
      lists[size_t(c)].splats.clear();
      if (!timed && owns_chain(sc, c)) {
        quota[size_t(c)] = chain_quota(sc, c) - r.mutations[size_t(c)];
        busy |= quota[size_t(c)] > 0;
      }
    }
    busy |= timed;
    ++r.rounds;
    if (stop.load()) break;
    if (sc.after_round) sc.after_round(r.rounds);
  }
  progress.finish();
  for (int64_t m : r.mutations) r.total_mutations += m;
  r.interrupted = options.stop && options.stop->load();
  r.partial = r.interrupted || (!timed && r.total_mutations < own_total);
  r.seconds = timer.seconds();
  return r;
}

}  // namespace dp::integrators
