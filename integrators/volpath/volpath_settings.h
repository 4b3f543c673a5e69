// Settings of the volumetric path tracer (`--integrator volpath`). Each key is read with
// its default and documentation in volpath_settings.cpp and written to the sidecar.
#pragma once

#include <cstdint>

#include "integrators/path/path_settings.h"
#include "integrators/settings.h"

namespace dp::integrators {

// Deliberate defects that the tests' statistical checks must reject
// (tests/integrators/test_volpath.cpp). C++ only: no scene key or --set reaches them, and
// the default (none) leaves every image bit-identical.
enum class VolpathFault : uint8_t {
  none,
  nee_without_transmittance,  // NEE ignores the medium's transmittance along the shadow ray
  pass_without_probability,   // a segment passing the medium weighted Tr, not Tr / P(pass)
  medium_nee_without_mis,     // NEE at medium vertices weighted 1 (phase sampling still MIS-weighted)
};

struct VolpathSettings {
  int rr_depth = 5;     // Russian roulette starts after this many segments
  bool nee = true;      // next-event estimation (light sampling) with MIS, at surface and medium vertices
  bool hide_emitters = false;  // drop directly visible emitters (depth 1)
  VolpathFault fault = VolpathFault::none;  // tests only, never read from settings

  static VolpathSettings read(Settings& s);
  // `path` on a scene with media (path_integrator.h).
  static VolpathSettings from_path(const PathSettings& p);
};

}  // namespace dp::integrators
