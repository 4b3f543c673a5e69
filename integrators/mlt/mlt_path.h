// `mlt --set mutations=path`: Metropolis light transport over path space (Veach 1997,
// Ch. 11) with the mutations of mcmc/ (so far Veach's bidirectional mutation,
// mcmc/mut_bidir.h). The normalisation b and the start paths come from BDPT samples
// (mcmc/path_seed.h); `chains` chains run in rounds (chain_scheduler.h: the image
// depends on the seed and the chain count, not on the thread count); every step splats
// the current path with weight 1 - a and the proposal with a (Veach 1997, Sec. 11.3.3);
// image = b W H / mutations * splats (McmcDriver's scale). Unlike PSSMLT, b is the
// seeder's alone (no large steps). As Mitsuba 0.6 (directSamples), paths of at most 2
// segments are rendered by the path tracer (integrators/direct_pass.h) and left out of the
// chains (seeds, b and mutation lengths start at 3 segments): the light seen directly is a
// path the mutations handle badly (only the bidirectional mutation changes it), and at
// equal time it dominated the squared error (cornell_specular, 20 s: MSE 0.040 with the
// chains doing it, 0.0035 without). By default the direct pass is interleaved with the
// chains' rounds at one sample per pixel per mutation per pixel (as gdmlt), so its error
// falls with the budget: a fixed 16 spp (Mitsuba's default) left a floor of MSE ~0.004
// that longer renders could not lower.
#pragma once

#include "core/json.h"
#include "integrators/integrator.h"
#include "integrators/mlt/mlt_settings.h"

namespace dp::integrators {

// Counters and the progress label use `name` ("mlt" or "memlt").
RenderResult render_mlt_path(const scene::Scene& scene, const RenderOptions& options, const MltSettings& settings,
                             const std::string& name);
// The image of raw buffers (one render's, or the summed parts'; integrators/mcmc_raw.h):
// b W H / mutations * "splat", plus the direct pass's "direct" mean unless direct_spp = -1.
RenderResult finish_mlt_path(const core::RawImage& raw, const RenderOptions& options, const MltSettings& settings);

}  // namespace dp::integrators
