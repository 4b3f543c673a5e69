// The end of every gradient-domain integrator (G-PT, GD-MLT): screened Poisson
// reconstruction of (primal, dx, dy) in L2 and L1 (Lehtinen et al. 2013, Eq. 8; Manzi et
// al. 2014, Eq. 8), the separately rendered direct light added afterwards, and the
// layers "" (the chosen reconstruction), recon_l1, recon_l2, primal (+ direct), dx, dy,
// direct, with the solve times in info.
#pragma once

#include <string>

#include "core/image_io.h"
#include "integrators/integrator.h"
#include "reconstruct/problem.h"

namespace dp::integrators {

// Any kernel: solves `problem` (its primal without the direct light) in L2 and L1 on
// resolve_threads(options) threads and writes "", recon_l1, recon_l2, primal (+ direct)
// and direct. options.stop (SIGINT/SIGTERM) ends the L1 solve at its next reweighting:
// recon_l1 is then the last complete iterate, info says reconstruction_interrupted and
// the result is partial.
void add_reconstruction_layers(const reconstruct::Problem& problem, const core::Image& direct,
                               const std::string& shown, const RenderOptions& options, RenderResult& result);

// The forward-difference grid: the layers above, then dx and dy.
void add_gradient_layers(const core::Image& primal, const core::Image& dx, const core::Image& dy,
                         const core::Image& direct, float alpha, const std::string& shown,
                         const RenderOptions& options, RenderResult& result);

}  // namespace dp::integrators
