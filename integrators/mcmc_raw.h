// The raw buffers of the MCMC integrators (`mlt`, `memlt`, `gdmlt`; issue 17) besides
// their splat sums: what finish() needs to scale the splats, so that the parts of a
// render split by chains (chain_scheduler.h) merge into one image with ONE
// normalisation b and the mutation count of all parts:
//   image = b W H / mutations * splats          (McmcDriver's scale)
//   b     = (b.sum / b.n) * (factor.n > 0 ? factor.sum / factor.n : 1)
// b.* are the samples of the mean estimating b (the bootstrap's or the path seeder's,
// plus PSSMLT's large steps), factor.* GD-MLT path space's E[factor] (gdmlt_path.h).
// Every part evaluates the whole bootstrap (same seed: same samples, same start states,
// no communication) but records only its share of the samples (mcmc/sample_share.h),
// so the summed shares hold each sample once: the whole render's b, whatever the
// number of parts, and still an unbiased b when a part is missing. The mutation count
// is every part's own (under --time the parts reach different counts; the scale is
// right for their sum). The scalars live in one sum buffer "mcmc.norm" (RawImage holds
// per-pixel buffers only): pixel 0 = (b.sum, b.n, mutations), pixel 1 = (factor.sum,
// factor.n, 0), the counts as doubles (exact below 2^53); 24 bytes per pixel.
#pragma once

#include <cstdint>

#include "core/raw_image.h"
#include "integrators/integrator.h"
#include "mcmc/sample_share.h"

namespace dp::integrators {

struct McmcNorm {
  mcmc::SampleShare b;
  mcmc::SampleShare factor;  // n = 0: no second factor
  int64_t mutations = 0;

  double value() const;                  // b (0 without samples)
  double scale(int64_t pixels) const;    // b pixels / mutations (0 without mutations)
  void write(core::RawImage& raw) const;  // adds the buffers above (raw has its size)
  static McmcNorm read(const core::RawImage& raw);  // ValueError when absent
};

// A W x H RawImage with no buffers yet.
core::RawImage empty_raw(int width, int height);

// min_spp = max_spp = mutations per pixel; partial when options.spp > 0 and fewer than
// options.spp W H mutations were made; info b and mutations_per_pixel.
void fill_mcmc_counts(const McmcNorm& norm, int64_t pixels, const RenderOptions& options, RenderResult& result);

// For a raw part (RenderOptions::raw): mutations per pixel rounded down and up (a part
// has a share of the mutations: "not one sample" only when it made none).
void fill_part_counts(int64_t mutations, int64_t pixels, RenderResult& result);

// The options finish() gets from render(): spp 0 for a --time render (as merge and MPI).
RenderOptions finish_options(const RenderOptions& options);

}  // namespace dp::integrators
