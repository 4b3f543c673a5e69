// Settings of the unidirectional path tracer (`--integrator path`). Each key is read
// with its default and documentation in path_settings.cpp and written to the sidecar.
#pragma once

#include "integrators/settings.h"

namespace dp::integrators {

struct PathSettings {
  int rr_depth = 5;     // Russian roulette starts after this many segments
  bool nee = true;      // next-event estimation (light sampling) with MIS
  bool hide_emitters = false;  // drop directly visible emitters (depth 1)

  static PathSettings read(Settings& s);
};

}  // namespace dp::integrators
