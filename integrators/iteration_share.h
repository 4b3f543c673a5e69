// Which global iterations this render runs (render --part/--mpi, issue 17). Part k of n
// runs the global iterations k, k + n, k + 2n, ... of the single render: whole
// iterations (a photon map needs every light path; a reuse tiling covers the image),
// each with its global index's radius, tiling and random streams, so the parts' summed
// buffers are the single render's. Shared by the iteration-based integrators (vcm, gpm,
// gvcm through photon_iterations, vpm/bre, gvpm, pr/gpr).
#pragma once

#include <algorithm>
#include <cstdint>

#include "integrators/integrator.h"

namespace dp::integrators {

struct IterationShare {
  int64_t parts = 1, part = 0;
  int64_t target = 0;  // this part's iterations in --spp mode (0 with a --time budget)

  // `least`: the fewest iterations a --spp render runs in all (pr/gpr: 1, as every pixel
  // needs a sample; the photon integrators: 0).
  explicit IterationShare(const RenderOptions& options, int64_t least = 0)
      : parts(std::max(1, options.parts)), part(options.part) {
    if (options.time_budget <= 0) target = (std::max<int64_t>(options.spp, least) + parts - 1 - part) / parts;
  }
  // The global index of this part's `local`-th iteration.
  int64_t global(int64_t local) const { return part + local * parts; }
};

}  // namespace dp::integrators
