// Settings of gradient-domain path tracing (`--integrator gpt`, Kettunen et al. 2015).
// Each key is read with its default and documentation in gpt_settings.cpp and written
// back into the sidecar.
#pragma once

#include <string>

#include "gradients/shift.h"
#include "gradients/volume_path_shift.h"
#include "integrators/settings.h"

namespace dp::integrators {

// A deliberate defect of the symmetric MIS weight, for the tests' negative controls.
enum class MisFault : uint8_t {
  none,
  // w = 1 / (1 + (p_i,other/p_self)^2): normalised over pixel i's two techniques only,
  // the offset pixel's p_j,t(T x)|T'| left out (Kettunen 2015, Sec. 4 and gradients/mis.h
  // normalise over all four), so the weights of a pair's four ways sum to about 2.
  without_offset,
};

// A deliberate defect of the shift in media (GptMediaTracer): the offset's reconnected
// edge x1' -> x2 without its transmittance tau (Gruson et al. 2018, Eq. 2).
enum class MediaShiftFault : uint8_t { none, offset_edge_without_transmittance };

// Deliberate defects that the tests' statistical checks must reject (test_gpt_unbiased.cpp,
// test_gpt_glossy.cpp). C++ only: GptSettings::read never sets them, no scene key or --set
// reaches them, and the default (none) leaves every image bit-identical.
struct GptFaults {
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shift
  MisFault mis = MisFault::none;
  gradients::VolumeShiftFault volume = gradients::VolumeShiftFault::none;  // media: reconnection factor
  MediaShiftFault media = MediaShiftFault::none;                          // media: edge transmittance
};

struct GptSettings {
  int rr_depth = 5;               // Russian roulette after this many segments (as PT)
  bool nee = true;                // next-event estimation (as PT)
  float shift_threshold = 0.001f; // roughness <= threshold: glossy/specular (half-vector copy)
  float alpha = 0.2f;             // screened Poisson weight of the primal
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  std::string shift = "reconnection";  // reconnection (Kettunen 2015) | manifold (gradients/manifold_shift.h)
  std::string manifold_chains = "emitter";  // shift=manifold: walk chains ending on an emitter | all
  std::string manifold_walk = "fallback";   // shift=manifold: walk where the copy misses | always
  GptFaults faults;                         // tests only, never read from settings (see GptFaults)

  static GptSettings read(Settings& s);
};

}  // namespace dp::integrators
