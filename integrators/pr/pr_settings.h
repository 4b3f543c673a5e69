// Settings of generalized path reusing (`--integrator pr`, Bauszat et al. 2017, Sec. 3.1).
// Each key is read with its default and documentation in pr_settings.cpp and written back
// into the sidecar.
#pragma once

#include <cstdint>

#include "gradients/shift.h"
#include "integrators/settings.h"

namespace dp::integrators {

// A deliberate defect of the tile's MIS weights, for the tests' negative controls.
enum class PrMisFault : uint8_t {
  none,
  // Every pixel of the tile weighted 1/N (N = the tile's pixel count) instead of the
  // balance heuristic of Eq. 3: right only where every reuse succeeds, so a tile with
  // failed shifts (occlusion, pixels beyond an edge) is biased low.
  uniform,
};

// Deliberate defects that the tests' statistical checks must reject (test_pr.cpp). C++
// only: PrSettings::read never sets them, no scene key or --set reaches them, and the
// default (none) leaves every image bit-identical.
struct PrFaults {
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shift
  PrMisFault mis = PrMisFault::none;
  // R without ReconnectionShiftOptions::match_classes: shifts of one walk may take other
  // strategies from other pixels, so they do not compose and the tile-constant weights of
  // a tile straddling glossy and diffuse surfaces no longer sum to one.
  bool any_class = false;
  // Occluded light samples counted as reusable (their NEE density in the weights, the
  // base's reused) while a blocked BSDF reconnection fails: NEE and BSDF weights of one
  // path then see different sampler sets (+4% under an environment map).
  bool occluded_nee = false;
};

struct PrSettings {
  int tile = 6;                     // T: reuse tiles of T x T pixels (the paper finds 6-8 best)
  int rr_depth = 5;                 // Russian roulette after this many segments (as PT)
  bool nee = true;                  // next-event estimation (as PT)
  float shift_threshold = 0.05f;    // roughness <= threshold: glossy/specular (half-vector copy)
  bool hide_emitters = false;       // drop directly visible emitters (depth 1), as PT's key
  PrFaults faults;                  // tests only, never read from settings (see PrFaults)

  static PrSettings read(Settings& s);
};

}  // namespace dp::integrators
