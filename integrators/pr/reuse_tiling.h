// Jittered tiling of path reusing (Bauszat et al. 2017, Sec. 3.3): the image is cut into
// T x T reuse tiles whose grid is offset by (ox, oy) in [0, T)^2, drawn per iteration from
// the seed alone, so no tile edge persists over iterations and a render depends only on
// the seed. Tiles at the image border are clipped (fewer pixels). Within one iteration the
// tiles are disjoint and cover every pixel once.
#pragma once

#include <cstdint>
#include <vector>

namespace dp::integrators {

struct ReuseTile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  int pixels() const { return width() * height(); }
};

struct ReuseTiling {
  int ox = 0, oy = 0;  // grid offset of this iteration
  std::vector<ReuseTile> tiles;
};

// The tiles of iteration `iteration` of a width x height image (`jitter` false: the grid
// at offset (0, 0) in every iteration, for tests that look at fixed tile borders).
ReuseTiling jittered_tiling(int width, int height, int tile, uint64_t seed, int64_t iteration, bool jitter = true);

}  // namespace dp::integrators
