// Settings of vertex connection and merging (`--integrator vcm`). Each key is read with
// its default and documentation in vcm_settings.cpp and written to the sidecar.
// max_depth comes from RenderOptions; `--spp` is the number of iterations (one light
// path per pixel and one camera path per pixel each).
#pragma once

#include <string>

#include "integrators/settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

// Strategy sets, as SmallVCM's algorithms (Georgiev et al. 2012):
//  vcm: connections (BDPT's s/t strategies) and merging, MIS over all of them;
//  bpt: connections only (in expectation the same image as `bdpt`; no photon grid);
//  vm:  merging at every camera vertex (bidirectional photon mapping), MIS over merges;
//       emission seen through Dirac lobes only (nothing else produces it);
//  ppm: merging at the first camera vertex whose path lobe is not Dirac, unweighted
//       (progressive photon mapping); emission seen through Dirac lobes only;
//  lt:  light tracing (t = 1) alone, unweighted.
enum class VcmMode { vcm, bpt, vm, ppm, lt };

struct VcmSettings {
  VcmMode mode = VcmMode::vcm;
  float radius = 0.003f;        // initial merging radius / scene bounding-sphere radius
  float radius_alpha = 0.75f;   // r_i = r_0 i^((alpha - 1) / 2) (Knaus & Zwicker 2011)
  int rr_depth = 5;             // Russian roulette on each subpath once it has this many segments
  pathspace::MisHeuristic heuristic = pathspace::MisHeuristic::power;
  bool adaptive_kernel = false;  // shrink the radius along the camera subpath (Sun et al. 2017, Sec. 6)

  bool connects() const { return mode == VcmMode::vcm || mode == VcmMode::bpt; }
  bool merges() const { return mode == VcmMode::vcm || mode == VcmMode::vm || mode == VcmMode::ppm; }
  bool light_traces() const { return connects() || mode == VcmMode::lt; }
  static std::string mode_name(VcmMode m);
  static VcmSettings read(Settings& s);
};

// The `adaptive_kernel` key of vcm and gvcm (pathspace/vcm_mis.h), with default `def`.
bool read_adaptive_kernel(Settings& s, bool def);

}  // namespace dp::integrators
