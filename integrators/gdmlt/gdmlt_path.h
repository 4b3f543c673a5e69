// `gdmlt --set mutations=path`: the chains of gradient-domain MLT over the extended path
// space with path-space mutations (Lehtinen et al. 2013, Sec. 5, and Manzi et al. 2014
// ran GD-MLT on Veach's and the manifold mutations): the mutations of `memlt`
// (integrators/path_chains.h) on states (x, j) with the target of mcmc/path_gradient.h.
//
// Seeding. The seeder's BDPT samples give b = integral of lum F and start paths with
// density lum F / b (mcmc/path_seed.h). The target's normalisation is
//   b_g = integral of lum F * factor = b * E[factor]   (x ~ lum F / b, u_pair uniform),
// estimated from `candidates` seeder paths with their own u_pair; the chains start from
// candidates resampled proportionally to their factor (sampling-importance-resampling
// again: start density -> f / b_g). Every candidate and start depends on the seed only.
// Splats (expected values, Veach 1997 Sec. 11.3.3): state z with weight w adds
// w F / f(z) to pixel i and w |N_i| weight_ij Delta^i_ij / f(z) to its kernel row; the
// buffers are scaled by b_g W H / mutations, as McmcDriver's.
#pragma once

#include "integrators/chain_scheduler.h"
#include "integrators/direct_pass.h"
#include "integrators/mcmc_raw.h"
#include "integrators/gdmlt/gdmlt_settings.h"
#include "kernels_adaptive/pair_kernel.h"
#include "mcmc/gradient_target.h"

namespace dp::integrators {

// Splat buffers of gdmlt (W H values each): the primal, the density (mutations per
// pixel), then the kernel's rows spread over as many buffers as they need (row r:
// buffer kGdmltRows + r / (W H), entry r % (W H)).
enum GdmltLayer { kGdmltPrimal = 0, kGdmltDensity = 1, kGdmltRows = 2 };

struct GdmltChains {
  ChainRunResult run;
  McmcNorm norm;                         // buffer value = norm.scale(W H) * splats
  mcmc::GradientTargetCounters target;   // the target's cases and shifts, chain order
};

// Parts (issue 17): every part draws every candidate and the same start states (b_g
// depends on the seed only); it runs chains c = part (mod parts) and its norm holds its
// share of the seeder's samples (b) and of the candidates (factor), mcmc_raw.h.
// Runs the chains (`options.time_budget` is theirs alone); `direct` catches up after
// every round when settings.direct_spp = 0. Adds gdmlt.* counters and info to `result`.
GdmltChains run_gdmlt_path(const scene::Scene& scene, const RenderOptions& options, const GdmltSettings& settings,
                           const kernels_adaptive::PairKernel& kernel, int layers, DirectPass& direct,
                           RenderResult& result);

}  // namespace dp::integrators
