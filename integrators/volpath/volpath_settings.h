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
  mnee_without_mis,           // MNEE and the paths it can also sample both weighted 1 (counted twice)
  mnee_planar_geometry,       // MNEE's D = 1 / |y - s_m|^2, the unrefracted last segment's
  light_tracing_without_mis,  // light tracing's splats weighted 1 (MNEE and BSDF sampling still count it)
  equiangular_without_mis,    // equiangular NEE weighted 1 (free-flight NEE and phase hits still MIS-weighted)
};

struct VolpathSettings {
  int rr_depth = 5;     // Russian roulette starts after this many segments
  bool nee = true;      // next-event estimation (light sampling) with MIS, at surface and medium vertices
  bool hide_emitters = false;  // drop directly visible emitters (depth 1)
  bool equiangular = true;     // equiangular NEE per medium segment, MIS with free flight (volpath_equiangular.cpp)
  bool mnee = true;            // manifold NEE through refractive surfaces (volpath_mnee.h; scenes with media)
  int mnee_max_chain = 4;      // most refractions MNEE solves for (1 .. kMaxMneeChain)
  bool mnee_shapes = false;  // MNEE also seeds at each specular shape (<= 4): a reflection off it, two refractions through it
  int mnee_seeds = 5;          // with mnee_scan 0: seed directions per connection (1: the straight line only; <= kMaxMneeSeeds)
  int mnee_scan = 24;          // seeds from a scan of this many directions (0: mnee_seeds' fixed seeds; volpath_mnee_scan.cpp)
  int mnee_iterations = 20;    // Newton steps of MNEE's manifold walk (Jakob & Marschner 2012)
  bool light_tracing = false;  // with MNEE, light paths through glass joined to the camera path, MIS with MNEE (volpath_light.cpp)
  VolpathFault fault = VolpathFault::none;  // tests only, never read from settings

  static VolpathSettings read(Settings& s);
  // `path` on a scene with media (path_integrator.h).
  static VolpathSettings from_path(const PathSettings& p);
};

}  // namespace dp::integrators
