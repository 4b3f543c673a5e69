// Reading the inputs of a reconstruction from files: a gradient render (one multi-layer
// EXR with layers `primal`, `dx`, `dy` and optionally `direct`, the layout the
// gradient-domain integrators write) or three separate EXRs. Throws dp::IoError for
// unreadable files and missing layers, dp::ValueError for size mismatches.
#pragma once

#include <optional>
#include <string>

#include "core/image.h"

namespace dp::reconstruct {

struct GradientImages {
  core::Image primal, dx, dy;
  // Direct illumination rendered separately; added to the reconstruction after the
  // solve (Manzi et al. 2014, Sec. 5: gradients cover indirect light only).
  std::optional<core::Image> direct;
};

GradientImages read_gradient_render(const std::string& path);
GradientImages read_gradient_images(const std::string& primal, const std::string& dx, const std::string& dy);

}  // namespace dp::reconstruct
