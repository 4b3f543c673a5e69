#include "integrators/mlt/mlt_settings.h"

#include <cstdio>

#include "core/error.h"

namespace dp::integrators {

MltSettings MltSettings::read(Settings& s) { return read(s, MltSettings{}); }

MltSettings MltSettings::read(Settings& s, const MltSettings& defaults) {
  MltSettings m = defaults;
  m.large_step_prob = s.get_double("large_step_prob", m.large_step_prob,
                                   "probability that a mutation is a large step (fresh uniform primary samples)");
  m.bootstrap = s.get_int("bootstrap", int(m.bootstrap),
                          "independent samples estimating the normalisation b and seeding the chains");
  m.large_step_b = s.get_bool("large_step_b", m.large_step_b,
                              "estimate b from the bootstrap and every large step's f (both are independent uniform samples)");
  m.chains = s.get_int("chains", m.chains,
                       "independent Markov chains (0: 4 per thread, the image then depends on --threads; 16 per part for --part/--mpi)");
  m.rr_depth = s.get_int("rr_depth", m.rr_depth, "Russian roulette only after this many path segments");
  m.nee = s.get_bool("nee", m.nee, "next-event estimation with power-heuristic MIS inside each path");
  const std::string mutations = s.get_string(
      "mutations", m.path_space ? "path" : "pss", "state space of the chains: pss (primary samples, Kelemen) | path (Veach's path-space mutations)",
      {"pss", "path"});
  m.path_space = mutations == "path";
  m.path_mutations.read(s);
  m.direct_spp = s.get_int("direct_spp", m.direct_spp,
                           "mutations=path: paths of <= 2 segments (emitters seen directly, direct lighting) rendered by "
                           "the path tracer and left out of the chains (Mitsuba's directSamples): N samples per pixel "
                           "first, 0 = interleaved with the chains (as many samples per pixel as mutations per pixel), "
                           "-1 = the chains render them too");
  if (m.direct_spp < -1) throw ValueError("setting 'direct_spp' must be >= -1", "--set");
  const std::string replay = s.get_string(
      "replay", "",
      "mutations=path: CHAIN:STEP re-runs one chain to that step (no image) and writes its path, strategies and last "
      "proposal into the JSON sidecar (info.replay)");
  if (!replay.empty()) {
    long long chain = -1, step = -1;
    char tail = 0;
    if (std::sscanf(replay.c_str(), "%lld:%lld%c", &chain, &step, &tail) != 2 || chain < 0 || step < 0 ||
        chain > 1000000)
      throw ValueError("setting 'replay' must be CHAIN:STEP with non-negative integers, got '" + replay + "'", "--set");
    if (!m.path_space) throw ValueError("setting 'replay' needs mutations=path", "--set");
    m.replay_chain = int(chain);
    m.replay_step = step;
  }
  if (!(m.large_step_prob > 0.0 && m.large_step_prob <= 1.0))
    throw ValueError("setting 'large_step_prob' must be in (0, 1]", "--set");
  if (m.bootstrap < 1) throw ValueError("setting 'bootstrap' must be >= 1", "--set");
  if (m.chains < 0) throw ValueError("setting 'chains' must be >= 0", "--set");
  if (m.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return m;
}

}  // namespace dp::integrators
