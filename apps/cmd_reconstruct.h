// `deltapath reconstruct`: screened Poisson reconstruction of a gradient render
// (reconstruct/ layer) from the command line.
#pragma once

#include <CLI/CLI.hpp>

namespace dp::apps {

// Adds the `reconstruct` subcommand:
//   deltapath reconstruct (--in RENDER.exr | --primal P.exr (--dx DX.exr --dy DY.exr | --pairs G.exr))
//       [--norm l1|l2] [--alpha A] [--threads N] --out OUT.exr
// RENDER.exr holds layers primal and dx, dy or the pair layers of any kernel
// (reconstruct/pair_layers.h), and optionally direct (subtracted from the primal, added
// to the result after the solve: reconstruct/render_io.h). Writes OUT.exr and a PNG preview next to it (OUT.png).
// User errors throw dp::Error.
void register_reconstruct(CLI::App& app);

}  // namespace dp::apps
