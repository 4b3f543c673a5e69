// SampleStream: the only source of randomness for building paths (DESIGN.md).
//  * IndependentStream wraps a core::Rng (Monte Carlo).
//  * PrimarySampleStream records every value it hands out and replays them on the next
//    build (Kelemen et al. 2002, primary sample space): rewind() restarts the walk at the
//    first coordinate; coordinates past the recorded ones are drawn from its Rng and
//    appended (lazy regeneration). The MCMC layer mutates values through mutable_samples().
// Consumers draw a fixed number of coordinates per vertex (path_builder.h documents the
// layout), so coordinate i always drives the same decision of the same vertex.
#pragma once

#include <cstddef>
#include <vector>

#include "core/rng.h"

namespace dp::pathspace {

class SampleStream {
 public:
  virtual ~SampleStream() = default;
  // Uniform in [0, 1).
  virtual float next() = 0;
  Vec2 next2() {
    const float a = next();
    return Vec2(a, next());
  }
};

class IndependentStream final : public SampleStream {
 public:
  explicit IndependentStream(core::Rng& rng) : m_rng(rng) {}
  float next() override { return m_rng.uniform(); }

 private:
  core::Rng& m_rng;
};

class PrimarySampleStream final : public SampleStream {
 public:
  explicit PrimarySampleStream(core::Rng& rng) : m_rng(rng) {}
  float next() override;
  // Restart at coordinate 0; recorded values are replayed in order.
  void rewind() { m_index = 0; }
  // Forget everything (the next build draws fresh values).
  void clear() {
    m_samples.clear();
    m_index = 0;
  }
  size_t used() const { return m_index; }
  const std::vector<float>& samples() const { return m_samples; }
  std::vector<float>& mutable_samples() { return m_samples; }

 private:
  core::Rng& m_rng;
  std::vector<float> m_samples;
  size_t m_index = 0;
};

}  // namespace dp::pathspace
