// Settings of gradient-domain path tracing (`--integrator gpt`, Kettunen et al. 2015).
// Each key is read with its default and documentation in gpt_settings.cpp and written
// back into the sidecar.
#pragma once

#include <string>

#include "integrators/settings.h"

namespace dp::integrators {

struct GptSettings {
  int rr_depth = 5;               // Russian roulette after this many segments (as PT)
  bool nee = true;                // next-event estimation (as PT)
  float shift_threshold = 0.001f; // roughness <= threshold: glossy/specular (half-vector copy)
  float alpha = 0.2f;             // screened Poisson weight of the primal
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  std::string shift = "reconnection";  // reconnection (Kettunen 2015) | manifold (gradients/manifold_shift.h)
  std::string manifold_chains = "emitter";  // shift=manifold: walk chains ending on an emitter | all
  std::string manifold_walk = "fallback";   // shift=manifold: walk where the copy misses | always

  static GptSettings read(Settings& s);
};

}  // namespace dp::integrators
