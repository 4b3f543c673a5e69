// Integrator interface and registry. An integrator renders a committed scene into
// named image layers (the first is the final RGB image). Scheduling options common to
// all integrators are in RenderOptions; integrator-specific keys come through Settings.
// Adding an integrator = one line in the registry table in registry.cpp.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/json.h"
#include "core/raw_image.h"
#include "core/stats.h"
#include "integrators/settings.h"
#include "scene/scene.h"

namespace dp::integrators {

struct RenderOptions {
  int spp = 16;              // samples per pixel (ignored when time_budget > 0)
  double time_budget = 0;    // wall-clock seconds (steady_clock); 0 = use spp
  uint64_t seed = 0;
  int threads = 0;           // 0 = all hardware threads
  int max_depth = 8;         // path segments, camera to light (a directly seen light is 1)
  bool quiet = false;        // no progress bar
  const std::atomic<bool>* stop = nullptr;  // set asynchronously (Ctrl-C): stop at next tile
  // A share of a fixed-spp render (`render --part K/N`, issue 17): this process renders
  // only the work units (pass, tile) that tile_scheduler.h assigns to part `part` of
  // `parts` (0-based), with the same random streams the whole render would use.
  int part = 0, parts = 1;
  // Fill RenderResult::raw (sums and counts, for `--partial`) instead of the final layers.
  bool raw = false;
};

struct RenderResult {
  std::vector<core::NamedLayer> layers;  // layers[0] = final image (name "")
  core::Stats stats;
  core::Json info = core::Json::object();  // integrator-specific facts for the sidecar
  double wall_seconds = 0;
  int64_t min_spp = 0, max_spp = 0;  // per-pixel sample counts actually rendered
  bool partial = false;              // stopped before the requested budget
  core::RawImage raw;                // with RenderOptions::raw: the accumulation buffers
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  virtual RenderResult render(const scene::Scene& scene, const RenderOptions& options) = 0;
  // `render --partial` / `merge` (issue 17). An integrator that supports them renders
  // RenderResult::raw when RenderOptions::raw is set, honours part/parts, and turns raw
  // buffers (one render's, or the sum of its parts') into the layers render() would give
  // (options: spp requested, threads). The default refuses with a one-line error.
  virtual bool supports_raw() const { return false; }
  virtual RenderResult finish(const core::RawImage& raw, const RenderOptions& options) const;
  // Whether render() transports light through participating media. An integrator that
  // does not would render a scene with media as if it were vacuum: check_scene_support
  // refuses that combination.
  virtual bool renders_media() const { return false; }
  // ... including heterogeneous (grid) media (scene/media/grid_tracking.h).
  virtual bool renders_grid_media() const { return false; }
};

// Throws dp::ValueError (one line, naming the integrators that can) when `integrator`
// cannot render `scene` correctly: today, a scene with media and an integrator without
// media support, or a scene with grid media and an integrator that renders homogeneous
// media only.
void check_scene_support(const Integrator& integrator, const scene::Scene& scene);

using IntegratorFactory = std::function<std::unique_ptr<Integrator>(Settings&)>;

// Creates an integrator by name, reading its settings (then checks that every given
// key was known). Throws dp::ValueError for unknown names.
std::unique_ptr<Integrator> make_integrator(const std::string& name, Settings& settings);
std::vector<std::string> integrator_names();

}  // namespace dp::integrators
