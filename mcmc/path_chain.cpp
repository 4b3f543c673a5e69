#include "mcmc/path_chain.h"

#include <cmath>
#include <utility>

namespace dp::mcmc {

void PathChainCounters::merge(const PathChainCounters& o) {
  proposed += o.proposed;
  accepted += o.accepted;
  for (size_t i = 0; i < status.size(); ++i) status[i] += o.status[i];
  invalid += o.invalid;
}

PathChain::PathChain(const BidirMutation& mutation, uint64_t seed, uint64_t index)
    : m_mutation(&mutation), m_rng(seed, core::mix64(0x9A7C'0000'0000ull + index)) {}

void PathChain::start(const PathState& x) { m_x = x; }

PathStep PathChain::step() {
  PathStep st;
  st.current = {m_x.colour(), m_x.raster};
  ++m_counters.proposed;
  BidirChoice rec;
  const ProposalStatus status = m_mutation->sample(m_x, m_y, rec, m_rng, m_sides);
  ++m_counters.status[size_t(status)];
  if (status != ProposalStatus::ok) return st;
  const double a = m_mutation->acceptance(m_x, m_y, rec);
  if (!std::isfinite(a)) {
    ++m_counters.invalid;
    return st;
  }
  st.a = a;
  st.proposed = {m_y.colour(), m_y.raster};
  if (m_rng.uniform_double() < a) {
    std::swap(m_x, m_y);
    st.accepted = true;
    ++m_counters.accepted;
  }
  return st;
}

}  // namespace dp::mcmc
