// A Chain is safe to move: chains grown in a std::vector (reallocating, so every chain
// is moved several times) run exactly the steps of chains that never move. Before the
// fix a Chain's PrimarySampleStream referred to the chain's own Rng, so a moved chain
// read and advanced a destroyed Rng: `mlt` aborted with "double free or corruption" at
// 1 thread, and under ASan this test reports a heap-use-after-free (the sanitize label
// runs it); in a plain build the mismatch of the step sequences is undefined behaviour
// and need not show.
#include <catch2/catch.hpp>
#include <memory>
#include <vector>

#include "mcmc/chain.h"

using namespace dp;

namespace {
// f = 1 + u0 + 2 u1 (reads two coordinates, a third one with probability u0).
class RampTarget final : public mcmc::Target {
 public:
  mcmc::TargetValue evaluate(pathspace::SampleStream& stream) override {
    const float u0 = stream.next(), u1 = stream.next();
    mcmc::TargetValue t;
    t.f = 1.0 + double(u0) + 2.0 * double(u1);
    if (u0 > 0.5f) t.f += double(stream.next());
    t.raster = Vec2(u0, u1);
    return t;
  }
};
}  // namespace

TEST_CASE("mcmc: chains moved by vector reallocation run the same steps as chains that never move", "[unit]") {
  constexpr int kChains = 9, kSteps = 200;
  RampTarget target;
  mcmc::ChainOptions opt;
  std::vector<mcmc::Chain> moved;  // no reserve: grows by reallocation
  std::vector<std::unique_ptr<mcmc::Chain>> fixed;
  for (int c = 0; c < kChains; ++c) {
    moved.emplace_back(target, opt, 5, uint64_t(c));
    moved.back().start({0.25f, 0.75f});
    fixed.push_back(std::make_unique<mcmc::Chain>(target, opt, 5, uint64_t(c)));
    fixed.back()->start({0.25f, 0.75f});
  }
  std::vector<mcmc::Chain> moved_again = std::move(moved);  // and once more as a whole
  for (int c = 0; c < kChains; ++c)
    for (int s = 0; s < kSteps; ++s) {
      const mcmc::Step a = moved_again[size_t(c)].step(), b = fixed[size_t(c)]->step();
      REQUIRE(a.proposed.f == b.proposed.f);
      REQUIRE(a.accepted == b.accepted);
      REQUIRE(a.large == b.large);
    }
  // The comparison can fail: another chain index gives other steps.
  mcmc::Chain other(target, opt, 5, 100);
  other.start({0.25f, 0.75f});
  bool differs = false;
  for (int s = 0; s < kSteps; ++s) differs |= other.step().proposed.f != fixed[0]->step().proposed.f;
  REQUIRE(differs);
}
