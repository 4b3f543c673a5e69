// What one gradient-domain sample adds to the image buffers, collected first so that a
// sample with any non-finite value can be dropped whole (G-BDPT, G-PM, G-VCM): primal,
// direct and the forward differences of the 4-neighbour pairs (Manzi et al. 2015, Eq. 6;
// Sun et al. 2017, Eq. 21-23 -- one pair's weight w over both pixels' strategies).
#pragma once

#include <vector>

#include "gradients/gradient_buffers.h"

namespace dp::integrators {

constexpr int kPairDx[4] = {1, -1, 0, 0}, kPairDy[4] = {0, 0, 1, -1};  // neighbour nb's pixel offset

struct PairSplat {
  int x, y, layer;  // 0 primal, 1 direct, 2 dx, 3 dy
  Rgbd v;
};

struct PairSplats {
  std::vector<PairSplat> adds;
  bool pair_primal = true;  // primal = every pair's estimates of both pixels (as G-PT)

  void clear() { adds.clear(); }
  void add(int x, int y, int layer, const Rgbd& v) { adds.push_back({x, y, layer, v}); }
  // The pair (i = (px, py), j = its neighbour nb = (qx, qy)) of one base term: shifted
  // (`off` non-null: the offset's estimate f(Tx)|T'|/p(x)) with gradient weight w, or the
  // T_0 fallback with the base's own weight w_base (gradient -w_base f(x)/p(x)). With
  // pair_primal, a quarter of the pair's estimates goes to each pixel's primal.
  void pair(int nb, int px, int py, const Rgbd& base, const Rgbd* off, double w, double w_base);
  // The MIS-weighted pair of a base term with weight w_base (its strategy's weight among
  // the base pixel's) and the offset (value f(Tx)|T'|/p(x), the same strategy's weight
  // w_off among the offset's, ratio R = p(Tx)|T'|/p(x)): gradient weight
  // 1 / (1/w_base + R^beta / w_off) (Manzi 2015 Eq. 6 for beta = 1, Sun 2017 Eq. 21-23),
  // or the T_0 fallback when the offset is missing (`shifted` false, zero value, a zero
  // weight or ratio). `ignore_offset` (tests' MIS defect): weight w_base. True if paired.
  bool mis_pair(int nb, int px, int py, const Rgbd& base, double w_base, bool shifted, const Rgbd& off, double w_off,
                double R, double beta, bool ignore_offset);
  // A base term whose neighbour nb lies outside the image: its own estimate only.
  void unpaired(int px, int py, const Rgbd& base, double w_base);
  // Adds everything to `buf` and one sample to pixel (px, py); false (nothing added but
  // the sample count) if any value is not finite.
  bool flush(gradients::GradientBuffers& buf, int px, int py) const;
};

}  // namespace dp::integrators
