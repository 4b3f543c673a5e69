#include "mcmc/chain.h"

#include <algorithm>
#include <cmath>

namespace dp::mcmc {

double metropolis_acceptance(double fx, double fy) {
  if (!(fy > 0.0) || !std::isfinite(fy)) return 0.0;
  if (!(fx > 0.0)) return 1.0;
  return std::min(1.0, fy / fx);  // Veach 1997, Eq. 11.4 with T(x -> y) = T(y -> x)
}

void kelemen_small_step(const KelemenKernel& kernel, std::vector<float>& u, core::Rng& rng) {
  kernel.perturb_all(u, rng);
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
    : m_target(target), m_opt(options), m_rng(seed, core::mix64(0xC4A1'0000'0000ull + index)) {}

void Chain::start(const std::vector<float>& u) {
  pathspace::PrimarySampleStream stream(m_rng);
  stream.mutable_samples() = u;
  m_value = m_target.evaluate(stream);
  m_x = stream.samples();
}

Step Chain::step() {
  Step s;
  s.current = m_value;
  s.large = m_rng.uniform_double() < m_opt.large_step_prob;
  pathspace::PrimarySampleStream stream(m_rng);  // lives only for this step (see chain.h)
  std::vector<float>& y = stream.mutable_samples();
  y.swap(m_y);  // reuse the proposal buffer's allocation
  if (s.large) {
    y.clear();
    ++m_counters.large;
  } else {
    y.assign(m_x.begin(), m_x.end());
    m_opt.small_step(m_opt.kernel, y, m_rng);
    for (size_t i = 0; i < std::min(y.size(), size_t(std::max(0, m_opt.redraw_first))); ++i) y[i] = m_rng.uniform();
    ++m_counters.small;
  }
  stream.rewind();
  s.proposed = m_target.evaluate(stream);  // coordinates past x's are drawn uniformly (chain.h)
  if (!s.proposed.valid()) {
    ++m_counters.invalid;
    s.a = 0.0;
  } else {
    if (!(s.proposed.f > 0.0)) ++m_counters.zero;
    s.a = m_opt.acceptance(m_value.f, s.proposed.f);
  }
  s.accepted = s.a > 0.0 && m_rng.uniform_double() < s.a;
  if (s.accepted) {
    m_x.swap(y);  // y (now the old x) is overwritten by the next proposal
    m_value = s.proposed;
    ++(s.large ? m_counters.accepted_large : m_counters.accepted_small);
  }
  m_y.swap(y);
  return s;
}

}  // namespace dp::mcmc
