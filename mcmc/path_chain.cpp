#include "mcmc/path_chain.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace dp::mcmc {

void MutatorCounters::merge(const MutatorCounters& o) {
  proposed += o.proposed;
  accepted += o.accepted;
  for (size_t i = 0; i < status.size(); ++i) status[i] += o.status[i];
  acceptance_sum += o.acceptance_sum;
  for (size_t d = 0; d < proposed_by_depth.size(); ++d) {
    proposed_by_depth[d] += o.proposed_by_depth[d];
    accepted_by_depth[d] += o.accepted_by_depth[d];
  }
}

void PathChainCounters::merge(const PathChainCounters& o) {
  if (mutators.size() < o.mutators.size()) mutators.resize(o.mutators.size());
  for (size_t i = 0; i < o.mutators.size(); ++i) mutators[i].merge(o.mutators[i]);
  invalid += o.invalid;
  stuck += o.stuck;
}

PathChain::PathChain(std::vector<WeightedMutator> mutators, uint64_t seed, uint64_t index,
                     std::unique_ptr<PathTargetFactor> factor)
    : m_mutators(std::move(mutators)),
      m_factor(std::move(factor)),
      m_rng(seed, core::mix64(0x9A7C'0000'0000ull + index)) {
  m_counters.mutators.resize(m_mutators.size());
}

void PathChain::start(const PathState& x) { m_x = x; }

double PathChain::selection(const PathState& s, size_t i) const {
  double sum = 0.0, mine = 0.0;
  for (size_t j = 0; j < m_mutators.size(); ++j) {
    const double w = m_mutators[j].mutator->suitable(s) ? m_mutators[j].weight : 0.0;
    sum += w;
    if (j == i) mine = w;
  }
  return sum > 0.0 ? mine / sum : 0.0;
}

PathStep PathChain::step() {
  PathStep st;
  st.current = PathSplat::of(m_x);
  // Pick a suitable mutation with probability proportional to its weight.
  double total = 0.0;
  for (const auto& m : m_mutators) total += m.mutator->suitable(m_x) ? m.weight : 0.0;
  if (!(total > 0.0)) {
    ++m_counters.stuck;
    return st;
  }
  double u = m_rng.uniform_double() * total;
  size_t pick = 0;
  for (size_t j = 0; j < m_mutators.size(); ++j) {
    const double w = m_mutators[j].mutator->suitable(m_x) ? m_mutators[j].weight : 0.0;
    if (w <= 0.0) continue;
    pick = j;
    if (u < w) break;
    u -= w;
  }
  const Mutator& mut = *m_mutators[pick].mutator;
  st.mutator = int(pick);
  MutatorCounters& mc = m_counters.mutators[pick];
  const size_t depth = size_t(std::clamp(m_x.depth(), 0, MutatorCounters::kDepths - 1));
  ++mc.proposed;
  ++mc.proposed_by_depth[depth];
  MutationRecord rec;
  const ProposalStatus status = mut.sample(m_x, m_y, rec, m_rng, m_sides);
  ++mc.status[size_t(status)];
  st.status = status;
  if (status != ProposalStatus::ok) return st;
  const double sx = selection(m_x, pick), sy = selection(m_y, pick);
  double r = mut.ratio(m_x, m_y, rec) * sy / sx;
  if (m_factor) {  // the extended target: u_pair redrawn (symmetric), the factor ratio
    m_y.u_pair = m_rng.uniform_double();
    m_factor->evaluate(m_y);
    r *= m_x.factor > 0.0 ? m_y.factor / m_x.factor : 1.0;
  }
  // NaN must not pass as min(1, NaN) = 1; an infinite ratio is an accept.
  if (std::isnan(r) || r < 0.0) {
    ++m_counters.invalid;
    return st;
  }
  const double a = std::min(1.0, r);
  st.a = a;
  mc.acceptance_sum += a;
  st.proposed = PathSplat::of(m_y);
  if (m_rng.uniform_double() < a) {
    std::swap(m_x, m_y);
    st.accepted = true;
    ++mc.accepted;
    ++mc.accepted_by_depth[depth];
  }
  return st;
}

}  // namespace dp::mcmc
