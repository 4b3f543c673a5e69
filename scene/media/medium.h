// Participating media. Version 1 of the scene format has homogeneous media only; they
// are parsed and validated and flagged in Scene::caps(). Sampling: phase_function.h
// (Henyey-Greenstein), free_flight.h (distances, transmittance); which medium a ray is
// in: medium_interface.h. Rendered by `volpath` (`path` delegates to it).
#pragma once

#include <memory>
#include <string>

#include "core/math.h"
#include "scene/media/density_grid.h"

namespace dp::scene {

struct PhaseFunctionDesc {
  enum class Type { isotropic, hg } type = Type::isotropic;
  float g = 0;  // Henyey-Greenstein asymmetry in (-1, 1)
};

// A homogeneous medium, or -- with `density` set -- a heterogeneous one whose coefficients
// at x are density(x) x sigma_a, sigma_s (a grid medium: grid_tracking.h samples and
// attenuates it; its sigma_t is grey, equal in the three channels, checked by the
// loaders). `volpath` (and `path`, which delegates to it) and `bdpt` render grid media
// (Integrator::renders_grid_media).
struct HomogeneousMedium {
  std::string name;
  Rgb sigma_a = Rgb::Zero();
  Rgb sigma_s = Rgb::Zero();
  PhaseFunctionDesc phase;
  std::shared_ptr<const DensityGrid> density;  // null: homogeneous
  Rgb sigma_t() const { return sigma_a + sigma_s; }
  bool heterogeneous() const { return density != nullptr; }
};

}  // namespace dp::scene
