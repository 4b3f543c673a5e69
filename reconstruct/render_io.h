// Reading the inputs of a reconstruction from files: a gradient render (one multi-layer
// EXR with layers `primal` and either `dx`, `dy` (forward differences) or the pair
// layers `pairs.<k>`, `pairs.<k>.offset` of any pixel-pair kernel (pair_layers.h), and
// optionally `direct`: the layouts the gradient-domain integrators write) or three
// separate EXRs. Throws dp::IoError for unreadable files and missing layers,
// dp::ValueError for size mismatches and malformed pair layers.
//
// The integrators' `primal` layer is what one sees: indirect + direct. When a render has a
// `direct` layer, the gradients cover only the indirect part (Manzi et al. 2014, Sec. 5;
// Kettunen et al. 2015, Sec. 6), so read_gradient_render returns primal - direct as the
// primal of the solve and the caller adds `direct` back after it.
#pragma once

#include <optional>
#include <string>

#include "core/image.h"
#include "reconstruct/pair_layers.h"
#include "reconstruct/problem.h"

namespace dp::reconstruct {

struct GradientImages {
  core::Image primal;  // of the solve (without `direct`)
  core::Image dx, dy;  // forward differences; empty when `pairs` is used
  PairLayers pairs;    // a pair-kernel render; empty values for a dx/dy render
  // Direct illumination rendered separately; added to the reconstruction after the
  // solve (Manzi et al. 2014, Sec. 5: gradients cover indirect light only).
  std::optional<core::Image> direct;
};

GradientImages read_gradient_render(const std::string& path);

// The screened Poisson problem of a read render (grid or pair kernel). Throws dp::ValueError.
Problem make_render_problem(GradientImages images, float alpha, const std::string& where);
GradientImages read_gradient_images(const std::string& primal, const std::string& dx, const std::string& dy);
// A primal EXR and a pair-gradient EXR (its pairs.<k> and pairs.<k>.offset layers).
GradientImages read_pair_images(const std::string& primal, const std::string& pairs);

}  // namespace dp::reconstruct
