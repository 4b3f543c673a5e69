// `render --mpi` (issue 17): rank r of N renders share r of N (RenderOptions::part/parts,
// the same disjoint (pass, tile) work units as `render --part r+1/N`, tile_scheduler.h)
// into raw sums and counts; rank 0 gathers every rank's buffers and counters, adds them in
// rank order -- what `merge` does with the files of `--partial --part`, so the result is
// bit-identical to merging those files and to a single-process render -- runs the
// integrator's finish (the Poisson reconstruction for gpt) once and writes the usual
// EXR/PNG/JSON with "ranks", per-rank wall seconds and the bytes gathered.
#pragma once

#include <string>

#include "apps/mpi_world.h"
#include "core/json.h"
#include "integrators/integrator.h"

namespace dp::apps {

// After `integrator` rendered this rank's share into result.raw: gathers to rank 0, which
// writes `out` with `side` (the sidecar fields of the render). Other ranks write nothing.
void mpi_reduce_and_write(const MpiWorld& world, const integrators::Integrator& integrator,
                          const integrators::RenderOptions& options, const integrators::RenderResult& result,
                          core::Json side, const std::string& out);

}  // namespace dp::apps
