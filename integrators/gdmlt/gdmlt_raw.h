// The raw buffers of `gdmlt` (issue 17: `render --partial`, `merge`, `--mpi`) and the
// finish() that turns them into the render's layers. A part (RenderOptions::part/parts)
// runs chains c = part (mod parts) of the whole chain set (chain_scheduler.h) and the
// direct pass's (pass, tile) units of its share (direct_pass.h); the Poisson
// reconstruction runs once, on the summed buffers:
//   sums   "primal", "density", "rows.<k>" (the kernel's rows, gdmlt_path.h's layers),
//          "direct" (+ count), the normalisation of integrators/mcmc_raw.h;
//   per-pixel buffers every part computes alike from the seed (the feature pass of
//   kernel=adaptive: "features.normal/albedo/depth"; INCMW's "ao") are stored by one
//   part per pixel (pixel p by part p mod parts, the others add 0) with the count
//   "features.n" (1 where stored): the sum of all parts is the single render's buffer,
//   exactly, so finish() rebuilds the very adaptive kernel the chains used. A merge that
//   lacks a part cannot rebuild it (an error says so); the standard kernel needs nothing.
#pragma once

#include <memory>

#include "core/raw_image.h"
#include "gradients/ao_map.h"
#include "integrators/chain_scheduler.h"
#include "integrators/gdmlt/gdmlt_settings.h"
#include "integrators/integrator.h"
#include "integrators/mcmc_raw.h"
#include "kernels_adaptive/features.h"
#include "kernels_adaptive/pair_kernel.h"

namespace dp::integrators {

// The pair kernel of the settings: standard, or adaptive from `features`.
kernels_adaptive::PairKernel gdmlt_kernel(const GdmltSettings& settings, const kernels_adaptive::Features& features,
                                          int width, int height);

// The raw buffers of a render: the chains' layers (run.sums), its normalisation, the
// replicated buffers (features when the kernel is adaptive, `ao` when not null).
core::RawImage gdmlt_raw(const ChainRunResult& run, const McmcNorm& norm, const kernels_adaptive::Features& features,
                         const gradients::AoMap* ao, const GdmltSettings& settings, const RenderOptions& options,
                         int width, int height);

// Adds to `result` the layers render() gives (and min/max spp, partial, solve times, b),
// from one render's raw buffers or the sum of its parts'.
void add_gdmlt_layers(const core::RawImage& raw, const RenderOptions& options, const GdmltSettings& settings,
                      RenderResult& result);

}  // namespace dp::integrators
