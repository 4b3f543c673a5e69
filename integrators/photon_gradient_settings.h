// Settings shared by the gradient-domain photon integrators (`gpm`, `gvcm`; Sun et al.
// 2017): the merging kernel, Russian roulette, the gradient MIS heuristic, the screened
// Poisson reconstruction and the chain walks. read_common() reads each key with its
// default and documentation (photon_gradient_settings.cpp).
#pragma once

#include <string>

#include "integrators/settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

struct PhotonGradientSettings {
  float radius_scale = 1.0f;  // kernel radius in pixel footprints (kernel_footprint.h; Sun 2017, Sec. 6)
  float radius_alpha = 0.9f;  // per-iteration reduction r_i = r_1 i^((alpha - 1) / 2) (paper: 0.9)
  int rr_depth = 5;           // Russian roulette on each subpath after this many segments
  pathspace::MisHeuristic heuristic = pathspace::MisHeuristic::power;  // beta = 2 (Eq. 21-23) or balance
  float alpha = 0.3f;          // screened Poisson weight of the primal (paper's runs: 0.3)
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  bool manifold = true;               // walk specular chains (camera side b..c, photons' chains)

  double beta() const { return heuristic == pathspace::MisHeuristic::power ? 2.0 : 1.0; }
  // `radius_doc`: how this integrator uses the footprint radius.
  void read_common(Settings& s, const std::string& radius_doc);
};

}  // namespace dp::integrators
