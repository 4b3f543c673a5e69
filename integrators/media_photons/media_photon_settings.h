// Settings shared by the volumetric photon density estimators (`vpm`, `bre`). Each key is
// read with its default and documentation in media_photon_settings.cpp and written to the
// sidecar. max_depth comes from RenderOptions; `--spp` is the number of iterations (each:
// `photons` light paths, then one camera path per pixel).
// Defaults follow Gruson et al. 2018, Sec. 6.1 where the paper gives them: radius
// reduction alpha = 0.7; initial radius 0.15% (VPM) / 0.10% (BRE) of the scene's
// bounding-box diagonal; a uniform kernel. The paper deposits 1M photons per iteration on
// a 12-core machine; the default here is 100k light paths per iteration (`photons`), set
// photons=1000000 to match it.
#pragma once

#include <cstdint>
#include <string>

#include "integrators/settings.h"

namespace dp::integrators {

struct MediaPhotonSettings {
  int photons = 100000;          // light paths per iteration
  double radius_scale = 0.0015;  // r_1 as a fraction of the scene's bounding-box diagonal
  double radius_alpha = 0.7;     // progressive reduction (volume_kernel.h); 1 keeps r fixed
  int rr_depth = 5;              // Russian roulette after this many segments (photons and camera paths)

  // Reads the keys with `radius_default` as radius_scale's default (the current `photons`
  // is its default; `photons_doc` replaces its help text when given).
  void read_common(Settings& s, double radius_default, const char* photons_doc = nullptr);
};

}  // namespace dp::integrators
