// Settings of bidirectional path tracing (`--integrator bdpt`). Each key is read with its
// default and documentation in bdpt_settings.cpp and written to the sidecar. max_depth
// comes from RenderOptions (path segments; a directly seen light is depth 1).
#pragma once

#include "integrators/settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

struct BdptSettings {
  int rr_depth = 5;  // Russian roulette on each subpath once it has this many segments
  pathspace::MisConfig mis;  // heuristic from `mis`; mis.fault: tests only, never read from settings
  // `strategy=s,t`: only this strategy, unweighted (mis.unweighted); -1 = all with MIS.
  int only_s = -1, only_t = -1;

  static BdptSettings read(Settings& s);
};

}  // namespace dp::integrators
