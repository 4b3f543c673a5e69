// A dense density grid for heterogeneous media (issue 15): values at the nodes of an
// nx x ny x nz lattice spanning an axis-aligned box, trilinearly interpolated inside it
// and 0 outside -- the layout of Mitsuba's `gridvolume` and its binary `.vol` files, the
// grid format users already have:
//   bytes 0-2 'VOL', byte 3 version 3, int32 encoding (1 = float32), int32 nx, ny, nz,
//   int32 channels (1 here), 6 float32 bounds (x0 y0 z0 x1 y1 z1), then nx*ny*nz*channels
//   float32 values, x fastest: value[((z ny + y) nx + x) channels + c]
//   (all little-endian).
// A medium with a grid has sigma(x) = density(x) x its coefficients (medium.h).
#pragma once

#include <string>
#include <vector>

#include "core/math.h"

namespace dp::scene {

struct DensityGrid {
  int nx = 0, ny = 0, nz = 0;
  Vec3 lo{0, 0, 0}, hi{1, 1, 1};  // world-space box the lattice spans
  std::vector<float> values;      // nx*ny*nz, >= 0
  float max_value = 0;            // the majorant's density
  float min_value = 0;            // the smallest node value (inside the box the density is >= it)

  // Trilinear density at world point p (0 outside the box).
  float lookup(const Vec3& p) const;
  // The ray's parameter interval [t0, t1] inside the box, clipped to [0, t_max]; false if empty.
  bool clip(const Vec3& o, const Vec3& d, float t_max, float& t0, float& t1) const;
  // Checks sizes, values (finite, >= 0) and bounds, sets max_value and min_value; `where` names the source in errors.
  void finalize(const std::string& where);
};

// Reads a Mitsuba `.vol` file (1 channel, float32). Errors are one line naming the file:
// dp::IoError (cannot open, short read), dp::ParseError (bad header or values).
DensityGrid read_vol_file(const std::string& path);
// Writes one (tests, tools).
void write_vol_file(const std::string& path, const DensityGrid& grid);

}  // namespace dp::scene
