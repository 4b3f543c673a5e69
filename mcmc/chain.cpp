#include "mcmc/chain.h"

#include <cmath>

namespace dp::mcmc {

double metropolis_acceptance(double fx, double fy) {
  if (!(fy > 0.0) || !std::isfinite(fy)) return 0.0;
  if (!(fx > 0.0)) return 1.0;
  return std::min(1.0, fy / fx);  // Veach 1997, Eq. 11.4 with T(x -> y) = T(y -> x)
}

void ChainCounters::merge(const ChainCounters& o) {
  large += o.large;
  small += o.small;
  accepted_large += o.accepted_large;
  accepted_small += o.accepted_small;
  invalid += o.invalid;
  zero += o.zero;
}

double ChainCounters::acceptance_rate() const {
  const int64_t n = large + small;
  return n > 0 ? double(accepted_large + accepted_small) / double(n) : 0.0;
}

Chain::Chain(Target& target, const ChainOptions& options, uint64_t seed, uint64_t index)
    : m_target(target), m_opt(options), m_rng(seed, core::mix64(0xC4A1'0000'0000ull + index)), m_stream(m_rng) {}

void Chain::start(const std::vector<float>& u) {
  m_stream.clear();
  m_stream.mutable_samples() = u;
  m_value = m_target.evaluate(m_stream);
  m_x = m_stream.samples();
}

Step Chain::step() {
  Step s;
  s.current = m_value;
  s.large = m_rng.uniform_double() < m_opt.large_step_prob;
  std::vector<float>& y = m_stream.mutable_samples();
  if (s.large) {
    m_stream.clear();
    ++m_counters.large;
  } else {
    y.assign(m_x.begin(), m_x.end());
    m_opt.kernel.perturb_all(y, m_rng);
    ++m_counters.small;
  }
  m_stream.rewind();
  s.proposed = m_target.evaluate(m_stream);  // coordinates past x's are drawn uniformly (chain.h)
  if (!s.proposed.valid()) {
    ++m_counters.invalid;
    s.a = 0.0;
  } else {
    if (!(s.proposed.f > 0.0)) ++m_counters.zero;
    s.a = m_opt.acceptance(m_value.f, s.proposed.f);
  }
  s.accepted = s.a > 0.0 && m_rng.uniform_double() < s.a;
  if (s.accepted) {
    m_x.swap(y);  // the stream's vector is overwritten by the next proposal
    m_value = s.proposed;
    ++(s.large ? m_counters.accepted_large : m_counters.accepted_small);
  }
  return s;
}

}  // namespace dp::mcmc
