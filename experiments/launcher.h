// An experiment point rendered by a separate process (issue 17: the experiment file's
// `launcher:` key, e.g. `mpirun -np 4`): runs
//   <launcher...> <this deltapath> render SCENE --integrator I --set K=V ... --seed S
//     --max-depth D (--spp N | --time T) --threads T --quiet --out DIR/point.exr
// and reads back the layers and the sidecar, so a sweep scales out through the cluster's
// launcher without a new tool. Under mpirun the render is `render --mpi` (apps/
// mpi_render.h): bit-identical to the in-process render for `--spp` budgets.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image_io.h"
#include "core/json.h"
#include "integrators/integrator.h"

namespace dp::experiments {

struct LaunchedRender {
  std::vector<core::NamedLayer> layers;
  int64_t min_spp = 0, max_spp = 0;
  double wall_seconds = 0;
  bool partial = false;
  core::Json counters = core::Json::object(), info = core::Json::object();
};

// Throws dp::Error naming the command when it cannot start or exits non-zero, or when
// its outputs are missing. `work_dir` receives the child's files (created, then removed).
LaunchedRender launch_render(const std::vector<std::string>& launcher, const std::string& scene,
                             const std::string& integrator,
                             const std::vector<std::pair<std::string, std::string>>& settings,
                             const integrators::RenderOptions& options, const std::string& work_dir);

}  // namespace dp::experiments
