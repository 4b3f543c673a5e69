// The discrete choices of the bidirectional mutation (Veach 1997, Sec. 11.4.2), in the
// form of Mitsuba 0.6 (docs/memlt_plan.md, Sec. 2.1): which vertices to delete, how many to
// insert, and how many of the new vertices the light side generates. The continuous part
// (the walks and the closing connection) and the density sum over the splits live with
// the mutator; this file is only the combinatorics, so that sample() and pmf() are tested
// against each other and against an enumeration (tests/mcmc/test_bidir_choice.cpp).
//
// Indices are EXTENDED: a path of depth K (x_0 on a light .. x_K the pinhole) gets a light
// supernode e = 0 before x_0 (the choice of a light position), x_i at e = i + 1, and a
// camera supernode e = K + 2 after the pinhole; the path has k = K + 2 extended edges.
//  1. new length k' ~ TwoTailedGeometric(2, centre k, [k_min, k_max]);
//  2. deletion length kd (edges; kd = 1 deletes no vertex) ~ TwoTailedGeometric(2,
//     centre 2, [max(k' == k ? 2 : 1, k - k' + 1), k]): with k' = k something must go;
//  3. ka = k' - k + kd new edges (ka - 1 new vertices);
//  4. l uniform over the admissible left ends: l in [0, k - kd] (in [1, k - kd - 1] when
//     kd = 1 or ka = 1: never delete only an endpoint sample, never insert between a
//     sample and its supernode) with e = l and e = l + kd both non-degenerate; m = l + kd;
//  5. s uniform on [s_min, s_max] = [0, ka - 1], s_min = 1 when l = 0 and the light
//     endpoint cannot be hit, s_max one less when m = k and the camera cannot be hit
//     (both checked; Mitsuba checks the second only when the first does not apply);
//     t = ka - 1 - s. The light walk takes s steps from e = l, the camera walk t steps
//     from e = m, and e = l + s connects to e = l + s + 1.
// pmf = P(k') P(kd) / |admissible l| / (s_max - s_min + 1), evaluated on the path it is
// given: the reverse move (reverse()) is evaluated on the proposal with its own list.
#pragma once

#include <cstdint>
#include <vector>

#include "pathspace/sample_stream.h"

namespace dp::mcmc {

struct BidirShape {
  int k = 0;                        // extended edges (depth + 2)
  std::vector<uint8_t> degenerate;  // per extended vertex 0 .. k: its distribution has measure zero
  bool light_hittable = true;       // a camera walk can end on the light endpoint (no delta lights)
  bool camera_hittable = false;     // a light walk can end on the camera (never for a pinhole)
};

struct BidirLengths {
  int k_min = 3, k_max = 10;  // admissible extended lengths (depth + 2)
};

struct BidirChoice {
  int l = 0, m = 0;  // kept vertices bounding the replaced range (extended indices)
  int ka = 0;        // new edges
  int s = 0;         // steps of the light-side walk from l (the camera side takes ka - 1 - s)
  int kd() const { return m - l; }
  int new_length(int k) const { return k - kd() + ka; }
  // The same move seen from the proposal back to the source (s is the reverse's to choose).
  BidirChoice reverse() const { return BidirChoice{l, l + ka, m - l, 0}; }
};

// Draws a choice for `shape` from four numbers of `stream`; false (nothing drawn past
// them) when no left end is admissible or the split range is empty.
bool sample_bidir_choice(const BidirShape& shape, const BidirLengths& lengths, pathspace::SampleStream& stream,
                         BidirChoice& out);
// Probability of `choice`'s (k', kd, l) and of one split s in its range (the same for
// every s), on `shape`; 0 if the choice is not one sample_bidir_choice can make.
double bidir_choice_pmf(const BidirShape& shape, const BidirLengths& lengths, const BidirChoice& choice);
// The split range [s_min, s_max] of a choice on `shape` (empty when s_min > s_max).
void bidir_split_range(const BidirShape& shape, const BidirChoice& choice, int& s_min, int& s_max);

}  // namespace dp::mcmc
