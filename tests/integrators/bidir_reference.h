// Test-local reference for bidirectional MIS (Veach 1997, Eq. 10.9): the densities of a
// full path x_0 (light) .. x_{n-1} (pinhole) from the light end and from the camera end,
// written straight from the definitions (not from pathspace/), the strategies that can
// generate it, their weights, and the subpaths of every split s' rebuilt from x's
// vertices. Dirac-derived densities are 1 (they cancel between the strategies that
// exist; the library stores 0 and remaps it to 1). Used by test_bdpt_mis and test_vcm_mis.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "pathspace/bidir_connect.h"

namespace dp::test {

using pathspace::BidirVertex;

bool is_dirac(const BidirVertex& v);
bool at_infinity(const BidirVertex& v);

struct Reference {
  std::vector<BidirVertex> x;
  std::vector<double> pl, pc;  // area density of x_i sampled from the light end / camera end
  std::vector<bool> valid;     // strategy s' (= number of light vertices) can generate x
  std::vector<double> weight;  // reference weight of s'
};

Reference reference(const scene::Scene& scene, std::vector<BidirVertex> x, bool power);
// Subpaths of split s' rebuilt from the reference path.
void split(const Reference& r, int sp, std::vector<BidirVertex>& light, std::vector<BidirVertex>& camera);

// Walks `samples` camera + light subpath pairs (stream (seed, k), rr_depth 3, depth <= max_depth)
// and calls fn(k, light, camera, s, t, connection, x) for every strategy (s, t) that connect()
// with `config` accepts; x is the full path y_0..y_{s-1} z_{t-1}..z_0.
using ConnectionVisitor =
    std::function<void(int k, const std::vector<BidirVertex>& light, const std::vector<BidirVertex>& camera, int s,
                       int t, const pathspace::Connection& connection, const std::vector<BidirVertex>& x)>;
void for_each_connection(const scene::Scene& scene, int max_depth, int samples, uint64_t seed,
                         const pathspace::MisConfig& config, const ConnectionVisitor& fn);

}  // namespace dp::test
