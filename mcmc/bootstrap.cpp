#include "mcmc/bootstrap.h"

#include <algorithm>
#include <atomic>

#include "core/thread_pool.h"

namespace dp::mcmc {

namespace {
core::Rng block_rng(uint64_t seed, int64_t block) {
  return core::Rng(seed, core::mix64(0xB007'0000'0000ull + uint64_t(block)));
}
}  // namespace

Bootstrap::Bootstrap(const TargetFactory& make, int64_t n, uint64_t seed, int threads) : m_seed(seed) {
  m_f.assign(size_t(std::max<int64_t>(n, 0)), 0.0);
  m_bad.assign(m_f.size(), 0);
  const int64_t blocks = (n + kBlock - 1) / kBlock;
  std::atomic<int64_t> invalid{0};
  core::parallel_for(blocks, threads, [&](int64_t block, int) {
    auto target = make();
    core::Rng rng = block_rng(m_seed, block);
    pathspace::PrimarySampleStream stream(rng);
    const int64_t end = std::min(n, (block + 1) * kBlock);
    for (int64_t i = block * kBlock; i < end; ++i) {
      stream.clear();
      const TargetValue v = target->evaluate(stream);
      if (!v.valid()) {
        invalid.fetch_add(1);
        m_bad[size_t(i)] = 1;
        continue;
      }
      m_f[size_t(i)] = std::max(0.0, v.f);
    }
  });
  m_invalid = invalid.load();
  m_cdf.resize(m_f.size());
  double sum = 0;
  for (size_t i = 0; i < m_f.size(); ++i) m_cdf[i] = sum += m_f[i];  // in index order: deterministic
  m_b = n > 0 ? sum / double(n) : 0.0;
}

SampleShare Bootstrap::share(int part, int parts) const {
  SampleShare s;
  for (size_t i = 0; i < m_f.size(); ++i)
    if (owns_sample(int64_t(i), kBlock, part, parts)) {
      s.sum += m_f[i];
      ++s.n;
      s.invalid += m_bad[i];
    }
  return s;
}

int64_t Bootstrap::select(double u) const {
  if (m_cdf.empty() || !(m_cdf.back() > 0.0)) return -1;
  const double t = u * m_cdf.back();
  auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), t);
  if (it == m_cdf.end()) --it;
  int64_t i = int64_t(it - m_cdf.begin());
  while (i > 0 && !(m_f[size_t(i)] > 0.0)) --i;  // never start at a zero sample
  return i;
}

std::vector<float> Bootstrap::replay(Target& target, int64_t i) const {
  const int64_t block = i / kBlock;
  core::Rng rng = block_rng(m_seed, block);
  pathspace::PrimarySampleStream stream(rng);
  for (int64_t j = block * kBlock; j <= i; ++j) {
    stream.clear();
    target.evaluate(stream);
  }
  return stream.samples();
}

}  // namespace dp::mcmc
