// Settings of gradient-domain bidirectional path tracing (`--integrator gbdpt`, Manzi et
// al. 2015). Each key is read with its default and documentation in gbdpt_settings.cpp
// and written to the sidecar. max_depth comes from RenderOptions.
#pragma once

#include <string>

#include "gradients/shift.h"
#include "integrators/settings.h"
#include "pathspace/bidir_mis.h"

namespace dp::integrators {

// Deliberate defects the tests' statistical checks must reject (test_gbdpt_unbiased.cpp).
// C++ only: GbdptSettings::read never sets them; none leaves every image bit-identical.
struct GbdptFaults {
  gradients::JacobianFault jacobian = gradients::JacobianFault::none;  // carried into the shifts
  bool mis_without_offset = false;  // gradient weight normalised over the base's strategies only
};

struct GbdptSettings {
  int rr_depth = 5;          // Russian roulette on each subpath after this many segments (as BDPT)
  pathspace::MisConfig mis;  // heuristic of the primal (as BDPT); the gradients use the balance heuristic
  float alpha = 0.2f;        // screened Poisson weight of the primal
  std::string reconstruction = "l1";  // which reconstruction is the RGB layer: l1 | l2
  std::string primal = "pairs";       // pairs (both pixels' pair estimates, as G-PT) | bdpt
  bool manifold = true;               // walk specular chains after b (Manzi 2015, Sec. 4)
  GbdptFaults faults;                 // tests only (see GbdptFaults)

  static GbdptSettings read(Settings& s);
};

}  // namespace dp::integrators
