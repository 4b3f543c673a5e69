#include "integrators/mlt/mlt_settings.h"

#include "core/error.h"

namespace dp::integrators {

MltSettings MltSettings::read(Settings& s) {
  MltSettings m;
  m.large_step_prob = s.get_double("large_step_prob", m.large_step_prob,
                                   "probability that a mutation is a large step (fresh uniform primary samples)");
  m.bootstrap = s.get_int("bootstrap", int(m.bootstrap),
                          "independent samples estimating the normalisation b and seeding the chains");
  m.large_step_b = s.get_bool("large_step_b", m.large_step_b,
                              "estimate b from the bootstrap and every large step's f (both are independent uniform samples)");
  m.chains = s.get_int("chains", m.chains,
                       "independent Markov chains (0: 4 per thread; the image then depends on --threads)");
  m.rr_depth = s.get_int("rr_depth", m.rr_depth, "Russian roulette only after this many path segments");
  m.nee = s.get_bool("nee", m.nee, "next-event estimation with power-heuristic MIS inside each path");
  const std::string mutations = s.get_string(
      "mutations", "pss", "state space of the chains: pss (primary samples, Kelemen) | path (Veach's path-space mutations)",
      {"pss", "path"});
  m.path_space = mutations == "path";
  m.mutators = s.get_string("mutators", m.mutators,
                            "path-space mutators (mutations=path): bidir (Veach's bidirectional mutation); lens, caustic, "
                            "multichain and manifold are not built yet",
                            {"bidir"});
  if (!(m.large_step_prob > 0.0 && m.large_step_prob <= 1.0))
    throw ValueError("setting 'large_step_prob' must be in (0, 1]", "--set");
  if (m.bootstrap < 1) throw ValueError("setting 'bootstrap' must be >= 1", "--set");
  if (m.chains < 0) throw ValueError("setting 'chains' must be >= 0", "--set");
  if (m.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return m;
}

}  // namespace dp::integrators
