// Participating media. Version 1 of the scene format has homogeneous media only; they
// are parsed and validated and flagged in Scene::caps(). Sampling: phase_function.h
// (Henyey-Greenstein), free_flight.h (distances, transmittance); which medium a ray is
// in: medium_interface.h. Rendered by `volpath` (`path` delegates to it).
#pragma once

#include <string>

#include "core/math.h"

namespace dp::scene {

struct PhaseFunctionDesc {
  enum class Type { isotropic, hg } type = Type::isotropic;
  float g = 0;  // Henyey-Greenstein asymmetry in (-1, 1)
};

struct HomogeneousMedium {
  std::string name;
  Rgb sigma_a = Rgb::Zero();
  Rgb sigma_s = Rgb::Zero();
  PhaseFunctionDesc phase;
  Rgb sigma_t() const { return sigma_a + sigma_s; }
};

}  // namespace dp::scene
