// Per-run image statistics for the Welch tests of integrators against PT
// (tests/support/welch.h): stats[0][run] = image mean, stats[1 + b][run] = mean of the
// b-th block x block pixel block (channel means), and the PT runs they are compared with.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "integrators/integrator.h"
#include "tests/support/quiet_options.h"

namespace dp::test {

using BlockStats = std::vector<std::vector<double>>;

inline void add_block_run(BlockStats& st, const core::Image& img, int block) {
  const int w = img.width(), h = img.height(), nbx = w / block, nby = h / block;
  if (st.empty()) st.assign(size_t(1 + nbx * nby), {});
  std::vector<double> blocks(size_t(nbx * nby), 0.0);
  double total = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = double(img(x, y).mean());
      total += v;
      if (x / block < nbx && y / block < nby) blocks[size_t((y / block) * nbx + x / block)] += v;
    }
  st[0].push_back(total / double(w * h));
  for (size_t b = 0; b < blocks.size(); ++b) st[1 + b].push_back(blocks[b] / double(block * block));
}

// `runs` independent PT renders (seeds 1000, 1001, ...) at `spp`.
inline BlockStats path_block_stats(const scene::Scene& s, int runs, int spp, int max_depth, int block) {
  BlockStats st;
  for (int r = 0; r < runs; ++r) {
    integrators::Settings settings;
    auto pt = integrators::make_integrator("path", settings);
    add_block_run(st, pt->render(s, quiet_options(spp, 1000 + uint64_t(r), max_depth)).layers[0].image, block);
  }
  return st;
}

}  // namespace dp::test
