#include "integrators/gpm/gpm_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/gpm/gpm_tracer.h"
#include "integrators/gradient_passes.h"
#include "integrators/tile_scheduler.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

namespace {

// The photon grid's cell radius: the median pixel footprint at z_b over a sparse set of
// pixel centres (queries of other radii stay exact, photon_grid.h); 0 if no camera path
// reaches a mergeable vertex.
double median_footprint(const scene::Scene& scene, int max_depth, int rr_depth) {
  const auto& cam = scene.camera();
  const int step_x = std::max(1, cam.width() / 32), step_y = std::max(1, cam.height() / 32);
  pathspace::SubpathParams params{max_depth + 1, rr_depth};
  params.stop_after_smooth = true;
  core::Rng rng(0x5eed, 17);
  std::vector<pathspace::BidirVertex> path;
  std::vector<double> r;
  for (int y = step_y / 2; y < cam.height(); y += step_y)
    for (int x = step_x / 2; x < cam.width(); x += step_x) {
      pathspace::camera_subpath(scene, Vec2(float(x) + 0.5f, float(y) + 0.5f), params, rng, path);
      for (int k = 1; k < int(path.size()); ++k)
        if (!path[size_t(k)].delta) {
          if (pathspace::vcm_mergeable(path[size_t(k)], false)) r.push_back(footprint_radius(scene, path.data(), k));
          break;
        }
    }
  if (r.empty()) return 0.0;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return r[r.size() / 2];
}

}  // namespace

RenderResult GpmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * h;
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const int64_t target = timed ? 0 : std::max(options.spp, 0);
  const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;
  const int64_t tiles = int64_t(tiles_x) * tiles_y;
  const double footprint = median_footprint(scene, options.max_depth, m_settings.rr_depth);
  const double grid_r0 = double(m_settings.radius_scale) *
                         (footprint > 0 ? footprint : 0.003 * double(std::max(scene.scene_radius(), 1e-3f)));

  VcmSettings light_settings;  // the light pass of VCM's photon mapping: photons, no light tracing
  light_settings.mode = VcmMode::ppm;
  light_settings.rr_depth = m_settings.rr_depth;
  GradientPasses passes;
  passes.total = gradients::GradientBuffers(w, h);
  std::vector<gradients::GradientBuffers> buffers(static_cast<size_t>(threads), gradients::GradientBuffers(w, h));
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads)), iter_stats(static_cast<size_t>(threads));
  std::vector<GpmScratch> scratch(static_cast<size_t>(threads));
  LightPathStore light;
  PhotonGrid grid;
  VcmLightCounters light_totals;
  int64_t photons = 0;
  core::Timer timer;
  core::Progress progress("gpm", timed ? 1000 : target, options.quiet);
  int64_t done = 0;
  double shrink = 1.0;
  while (timed ? timer.seconds() < options.time_budget : done < target) {
    if (options.stop && options.stop->load()) {
      passes.partial = true;
      break;
    }
    shrink = std::pow(double(done + 1), 0.5 * (double(m_settings.radius_alpha) - 1.0));
    VcmIteration it;
    it.index = done;
    it.seed = options.seed;
    it.max_depth = options.max_depth;
    it.radius = float(grid_r0 * shrink);
    VcmLightCounters lc;
    if (!trace_light_paths(scene, light_settings, it, pixels, threads, options.stop, light, lc)) {
      passes.partial = true;
      break;
    }
    light.gather_positions();
    grid.build(light.photon_pos, it.radius);
    if (!light.photon_pos.empty()) light.gather_photons(grid.order());
    const GpmTracer tracer(scene, m_settings, options.max_depth, double(m_settings.radius_scale) * shrink, light, grid);
    for (auto& s : iter_stats) s = core::Stats{};
    std::vector<char> tile_done(size_t(tiles), 0);
    core::parallel_for(
        tiles, threads,
        [&](int64_t ti, int thread) {
          const int x0 = int(ti % tiles_x) * kTileSize, y0 = int(ti / tiles_x) * kTileSize;
          core::Rng rng(options.seed, (uint64_t(done) << 32) | 0x80000000ull | uint64_t(ti));
          GpmCounters counters;
          for (int y = y0; y < std::min(h, y0 + kTileSize); ++y)
            for (int x = x0; x < std::min(w, x0 + kTileSize); ++x)
              tracer.sample(x, y, rng, scratch[size_t(thread)], buffers[size_t(thread)], counters);
          counters.flush(iter_stats[size_t(thread)]);
          tile_done[size_t(ti)] = 1;
        },
        options.stop);
    const bool complete = std::find(tile_done.begin(), tile_done.end(), 0) == tile_done.end();
    for (size_t t = 0; t < buffers.size(); ++t) {
      if (complete) {
        passes.total.merge(buffers[t]);
        thread_stats[t].merge(iter_stats[t]);
      }
      buffers[t].clear();
    }
    if (!complete) {  // an interrupted iteration is dropped whole
      passes.partial = true;
      break;
    }
    light_totals += lc;
    photons += int64_t(light.photon_pos.size());
    ++done;
    if (timed) progress.set_fraction(std::min(1.0, timer.seconds() / options.time_budget));
    else progress.advance();
  }
  progress.finish();
  passes.passes = passes.kept = done;
  passes.partial = passes.partial || (!timed && done < target);
  passes.render_seconds = timer.seconds();

  RenderResult result = gradient_result(passes, thread_stats, m_settings.alpha, m_settings.reconstruction, threads, m_json);
  result.stats.add("gpm.iterations", done);
  result.stats.add("gpm.light_paths", done * pixels);
  result.stats.add("gpm.light_vertices", light_totals.light_vertices);
  result.stats.add("gpm.photons", photons);
  result.info["radius_scale"] = double(m_settings.radius_scale);
  result.info["radius_footprint_median"] = footprint;  // pixel footprint at z_b, scene units
  result.info["radius_final_factor"] = double(m_settings.radius_scale) * shrink;
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace dp::integrators
