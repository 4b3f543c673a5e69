#include "integrators/path_chains.h"

#include <algorithm>

#include "core/error.h"
#include "core/rng.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

void PathMutationSettings::read(Settings& s) {
  const std::string list = s.get_string(
      "mutators", preset,
      "path-space mutations (mutations=path): veach (= bidir,lens,caustic,multichain), memlt (= veach + manifold) or a "
      "comma list of bidir (Veach's bidirectional mutation, needed: the only one that changes lengths), lens, caustic, "
      "multichain, manifold (Jakob & Marschner's manifold perturbation)");
  mutators.clear();
  if (list == "veach" || list == "memlt") {
    mutators = {"bidir", "lens", "caustic", "multichain"};
    if (list == "memlt") mutators.push_back("manifold");
  } else {
    size_t at = 0;
    while (at <= list.size()) {
      const size_t end = std::min(list.find(',', at), list.size());
      const std::string name = list.substr(at, end - at);
      if (name != "bidir" && name != "lens" && name != "caustic" && name != "multichain" && name != "manifold")
        throw ValueError("setting 'mutators': unknown mutation '" + name +
                             "' (bidir, lens, caustic, multichain, manifold, veach or memlt)",
                         "--set");
      mutators.push_back(name);
      at = end + 1;
    }
    if (std::find(mutators.begin(), mutators.end(), "bidir") == mutators.end())
      throw ValueError("setting 'mutators' must include bidir: the perturbations never change a path's length, so "
                       "without it the chain is not ergodic", "--set");
  }
  manifold_lambda = s.get_double("manifold_lambda", manifold_lambda,
                                 "manifold perturbation: vMF peak density lambda^2 max(1/(4 pi), p) (Jakob & Marschner 2012)");
  manifold_sensor_prob = s.get_double("manifold_sensor_prob", manifold_sensor_prob,
                                      "manifold perturbation: probability of starting at the pinhole");
  if (!(manifold_lambda > 0.0)) throw ValueError("setting 'manifold_lambda' must be > 0", "--set");
  if (!(manifold_sensor_prob >= 0.0 && manifold_sensor_prob <= 1.0))
    throw ValueError("setting 'manifold_sensor_prob' must be in [0, 1]", "--set");
}

namespace {
mcmc::BidirLengths lengths_of(int min_depth, int max_depth) {
  mcmc::BidirLengths l;
  l.k_min = min_depth + 2;  // extended lengths: depth + 2
  l.k_max = max_depth + 2;
  return l;
}
mcmc::ManifoldSettings manifold_of(const PathMutationSettings& s) {
  mcmc::ManifoldSettings m;
  m.lambda = s.manifold_lambda;
  m.sensor_prob = s.manifold_sensor_prob;
  return m;
}
}  // namespace

PathMutatorSet::PathMutatorSet(const scene::Scene& scene, const PathMutationSettings& settings, int min_depth,
                               int max_depth, mcmc::BidirMutationFault fault)
    : m_bidir(scene, lengths_of(min_depth, max_depth), fault),
      m_lens(scene),
      m_caustic(scene, m_lens.r1(), m_lens.r2()),
      m_multichain(scene, m_lens.r1(), m_lens.r2()),
      m_manifold(scene, manifold_of(settings)) {
  for (const std::string& m : settings.mutators)
    m_list.push_back({m == "lens"         ? static_cast<const mcmc::Mutator*>(&m_lens)
                      : m == "caustic"    ? static_cast<const mcmc::Mutator*>(&m_caustic)
                      : m == "manifold"   ? static_cast<const mcmc::Mutator*>(&m_manifold)
                      : m == "multichain" ? static_cast<const mcmc::Mutator*>(&m_multichain)
                                          : static_cast<const mcmc::Mutator*>(&m_bidir),
                      1.0});
}

mcmc::PathSeedOptions seed_options(const RenderOptions& options, int rr_depth, int64_t bootstrap, int min_depth) {
  mcmc::PathSeedOptions so;
  so.max_depth = options.max_depth;
  so.min_depth = min_depth;
  so.rr_depth = rr_depth;
  so.samples = bootstrap;
  so.seed = options.seed;
  so.threads = resolve_threads(options);
  return so;
}

int start_path(const mcmc::PathSeeder& seeder, uint64_t seed, int c, const std::string& name, mcmc::PathState& x) {
  core::Rng pick(seed, core::mix64(0x57A7'0000'0000ull + uint64_t(c)));
  mcmc::PathSides sides;
  int tries = 0;
  while (!seeder.select(pick.uniform_double(), x, sides))
    if (++tries == 100)
      throw Error(name + " (mutations=path): no BDPT seed path evaluates; cannot start chain " + std::to_string(c));
  return tries;
}

int64_t report_path_chains(RenderResult& result, const std::string& name,
                           const std::vector<mcmc::WeightedMutator>& mutators, const mcmc::PathChainCounters& sum) {
  int64_t proposed = 0, accepted = 0, nonfinite = 0;
  for (size_t i = 0; i < mutators.size() && i < sum.mutators.size(); ++i) {
    const mcmc::MutatorCounters& mc = sum.mutators[i];
    const std::string prefix = name + ".path." + mutators[i].mutator->name() + ".";
    result.stats.add(prefix + "proposed", mc.proposed);
    result.stats.add(prefix + "accepted", mc.accepted);
    for (size_t k = 0; k < mc.status.size(); ++k)
      if (k != size_t(mcmc::ProposalStatus::ok))
        result.stats.add(prefix + "fail." + mcmc::proposal_status_name(mcmc::ProposalStatus(k)), mc.status[k]);
    result.info[std::string("acceptance_") + mutators[i].mutator->name()] =
        mc.proposed > 0 ? double(mc.accepted) / double(mc.proposed) : 0.0;
    // Per path depth (segments of the current path): [depth, proposed, acceptance].
    core::Json by_depth = core::Json::array();
    for (size_t d = 0; d < mc.proposed_by_depth.size(); ++d)
      if (mc.proposed_by_depth[d] > 0) {
        core::Json row = core::Json::array();
        row.push_back(double(d));
        row.push_back(double(mc.proposed_by_depth[d]));
        row.push_back(double(mc.accepted_by_depth[d]) / double(mc.proposed_by_depth[d]));
        by_depth.push_back(row);
      }
    result.info[std::string("acceptance_by_depth_") + mutators[i].mutator->name()] = by_depth;
    proposed += mc.proposed;
    accepted += mc.accepted;
    nonfinite += mc.status[size_t(mcmc::ProposalStatus::nonfinite)];
  }
  result.stats.add(name + ".path.stuck", sum.stuck);
  result.stats.add(name + ".path.invalid", sum.invalid);
  result.info["acceptance_rate"] = proposed > 0 ? double(accepted) / double(proposed) : 0.0;
  return nonfinite + sum.invalid;
}

}  // namespace dp::integrators
