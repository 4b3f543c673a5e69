// Random numbers on Boost.Random. Every stream is created from an explicit
// (seed, stream id) pair; integrators use one stream per tile / chain / work item, so
// images are reproducible for a given seed (independent of scheduling).
#pragma once

#include <boost/random/mersenne_twister.hpp>
#include <cstdint>

#include "core/math.h"

namespace dp::core {

// SplitMix64 finalizer: decorrelates (seed, stream) pairs before seeding the engine.
uint64_t mix64(uint64_t x);

class Rng {
 public:
  explicit Rng(uint64_t seed = 0, uint64_t stream = 0);
  void seed(uint64_t seed, uint64_t stream);

  uint32_t next_u32() { return static_cast<uint32_t>(m_engine()); }
  // Uniform in [0, 1), 24-bit resolution (exactly representable floats).
  float uniform() { return float(next_u32() >> 8) * 0x1p-24f; }
  // Uniform in [0, 1), 53-bit resolution.
  double uniform_double() {
    const uint64_t a = next_u32() >> 5, b = next_u32() >> 6;
    return double(a * 67108864ull + b) * 0x1p-53;
  }
  Vec2 uniform2() {
    const float a = uniform();
    return Vec2(a, uniform());
  }
  // Uniform integer in [0, n).
  uint32_t uniform_index(uint32_t n) { return uint32_t((uint64_t(next_u32()) * n) >> 32); }

 private:
  boost::random::mt19937 m_engine;
};

}  // namespace dp::core
