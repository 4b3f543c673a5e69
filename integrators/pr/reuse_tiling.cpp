#include "integrators/pr/reuse_tiling.h"

#include <algorithm>

#include "core/rng.h"

namespace dp::integrators {

ReuseTiling jittered_tiling(int width, int height, int tile, uint64_t seed, int64_t iteration, bool jitter) {
  ReuseTiling t;
  // Its own stream (salted), apart from the tiles' sampling streams.
  core::Rng rng(seed, core::mix64(uint64_t(iteration) ^ 0x7469'6c65'6a69'7474ull));
  t.ox = int(rng.uniform_index(uint32_t(tile)));
  t.oy = int(rng.uniform_index(uint32_t(tile)));
  if (!jitter) t.ox = t.oy = 0;
  // Column c covers [c T - ox, (c + 1) T - ox) clipped to the image; same for rows.
  for (int y0 = -t.oy; y0 < height; y0 += tile)
    for (int x0 = -t.ox; x0 < width; x0 += tile) {
      ReuseTile r;
      r.x0 = std::max(0, x0);
      r.y0 = std::max(0, y0);
      r.x1 = std::min(width, x0 + tile);
      r.y1 = std::min(height, y0 + tile);
      if (r.x1 > r.x0 && r.y1 > r.y0) t.tiles.push_back(r);
    }
  return t;
}

}  // namespace dp::integrators
