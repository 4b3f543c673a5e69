// Shared helpers for the kernels_adaptive tests: synthetic feature buffers and the
// expected splats of exact gradients into a pair kernel's rows.
#pragma once

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "kernels_adaptive/features.h"
#include "kernels_adaptive/pair_kernel.h"

namespace dp::kernels_adaptive::test {

// Features already in [0, 1]: `regions` vertical bands of distinct normals (the band
// edges wobble with y), two albedos in a checker of 3x3 blocks, a depth ramp, plus small
// noise (below every tau), so a kernel gets symmetric and non-symmetric pairs.
inline Features synthetic_features(int w, int h, int regions, core::Rng& rng) {
  Features f;
  f.width = w;
  f.height = h;
  const Vec3 normals[3] = {{1.0f, 0.5f, 0.5f}, {0.5f, 1.0f, 0.5f}, {0.5f, 0.5f, 0.0f}};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int band = std::min(regions - 1, (x + (y % 3 == 0 ? 1 : 0)) * regions / w);
      const Vec3 noise(0.05f * rng.uniform(), 0.05f * rng.uniform(), 0.05f * rng.uniform());
      f.normal.push_back(normals[band % 3] + noise);
      f.albedo.push_back(((x / 3 + y / 3) % 2 == 0) ? Rgb(0.2f, 0.2f, 0.2f) : Rgb(0.25f, 0.2f, 0.2f));
      f.depth.push_back(0.02f * float(x + y) + 0.05f * rng.uniform());
    }
  return f;
}

// Expected row values when every pixel splats exact gradient parts: for each pair
// {i, j} the true I_i - I_j is split at random into Delta^i_ij + Delta^j_ij (Manzi et al.
// 2014, Eqs. 4-5), and pixel i adds w * Delta^i_ij to its entry's row (the |N_i| factor
// cancels the 1 / |N_i| chance of drawing j). The split depends only on the unordered
// pair, so both pixels of a pair see the same Delta_ij.
inline std::vector<Rgb> exact_splats(const PairKernel& k, const std::vector<Rgb>& image, uint64_t seed) {
  std::vector<Rgb> b(k.rows.size(), Rgb::Zero());
  for (int32_t i = 0; i < int32_t(image.size()); ++i)
    for (const auto& e : neighbours(k, i)) {
      const int32_t lo = std::min(i, e.j), hi = std::max(i, e.j);
      core::Rng rng(seed, uint64_t(lo) * image.size() + uint64_t(hi));
      const Rgb t(rng.uniform(), rng.uniform(), rng.uniform());  // Delta^lo_{lo,hi} / (I_lo - I_hi)
      const Rgb delta_lo_hi = image[size_t(lo)] - image[size_t(hi)];
      // Delta^i_ij: pixel i's part of I_i - I_j.
      const Rgb part = (i == lo) ? Rgb(t * delta_lo_hi) : Rgb(-(Rgb::Ones() - t) * delta_lo_hi);
      b[size_t(e.row)] += e.weight * part;
    }
  return b;
}

}  // namespace dp::kernels_adaptive::test
