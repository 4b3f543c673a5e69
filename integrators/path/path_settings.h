// Settings of the unidirectional path tracer (`--integrator path`). Each key is read
// with its default and documentation in path_settings.cpp and written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/settings.h"

namespace dp::integrators {

// A deliberate defect that the tests' statistical checks must reject
// (test_path_consistency.cpp). C++ only: PathSettings::read never sets it, no scene key
// or --set reaches it, and the default (none) leaves every image bit-identical.
enum class PathFault : uint8_t {
  none,
  nee_without_cosine,   // NEE contribution f * L / p without |cos theta_o| at the shading point
};

struct PathSettings {
  int rr_depth = 5;     // Russian roulette starts after this many segments
  bool nee = true;      // next-event estimation (light sampling) with MIS
  bool hide_emitters = false;  // drop directly visible emitters (depth 1)
  PathFault fault = PathFault::none;  // tests only, never read from settings (see PathFault)

  static PathSettings read(Settings& s);
};

}  // namespace dp::integrators
