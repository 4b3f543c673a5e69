#include "integrators/vcm/vcm_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/iteration_share.h"
#include "integrators/radiance_render.h"
#include "integrators/raw_result.h"
#include "integrators/tile_scheduler.h"
#include "integrators/vcm/vcm_camera.h"

namespace dp::integrators {

namespace {

struct Totals {
  VcmLightCounters light;
  VcmCameraCounters camera;
  int64_t photons = 0, grid_builds = 0;
};

void write_counters(const Totals& t, int64_t iterations, int64_t light_paths, core::Stats& stats) {
  stats.add("vcm.iterations", iterations);
  stats.add("vcm.light_paths", light_paths);
  stats.add("vcm.light_vertices", t.light.light_vertices);
  stats.add("vcm.camera_vertices", t.camera.camera_vertices);
  stats.add("vcm.connections", t.light.connections + t.camera.connections);
  stats.add("vcm.connections_occluded", t.light.occluded + t.camera.occluded);
  stats.add("vcm.splats", t.light.splats);
  stats.add("vcm.photons", t.photons);
  stats.add("vcm.grid_builds", t.grid_builds);
  stats.add("vcm.merge_queries", t.camera.merge_queries);
  stats.add("vcm.merges", t.camera.merges);
  stats.add("vcm.nan_dropped", t.light.nan_dropped + t.camera.nan_dropped);
}

}  // namespace

RenderResult VcmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int64_t pixels = int64_t(w) * h;
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const IterationShare share(options);
  const int64_t target = share.target;
  const float r0 = m_settings.radius * (scene.scene_radius() > 0.0f ? scene.scene_radius() : 1.0f);
  const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;

  std::vector<Rgbd> total(size_t(pixels), Rgbd::Zero());
  std::vector<Rgbd> iter(size_t(pixels), Rgbd::Zero());
  std::vector<VcmCameraScratch> scratch(static_cast<size_t>(threads));
  std::vector<VcmCameraCounters> tile_counters(size_t(tiles_x) * size_t(tiles_y));
  LightPathStore light;
  PhotonGrid grid;
  Totals totals;
  core::Timer timer;
  core::Progress progress("vcm", timed ? 1000 : target, options.quiet);
  int64_t done = 0;
  float radius = r0;
  bool interrupted = false;
  while (timed ? timer.seconds() < options.time_budget : done < target) {
    if (options.stop && options.stop->load()) {
      interrupted = true;
      break;
    }
    const int64_t global = share.global(done);
    VcmIteration it;
    it.index = global;
    it.seed = options.seed;
    it.max_depth = options.max_depth;
    it.radius = float(double(r0) / std::pow(double(global + 1), 0.5 * (1.0 - double(m_settings.radius_alpha))));
    it.mis.heuristic = m_settings.heuristic;
    it.mis.connections = m_settings.connects();
    it.mis.adaptive_kernel = m_settings.adaptive_kernel;
    it.mis.eta = m_settings.merges() ? float(kPiD * double(it.radius) * double(it.radius) * double(pixels)) : 0.0f;
    VcmLightCounters lc;
    if (!trace_light_paths(scene, m_settings, it, pixels, threads, options.stop, light, lc)) {
      interrupted = true;
      break;
    }
    if (m_settings.merges()) light.collect_photons(threads);
    if (m_settings.merges() && !light.photon_pos.empty()) {
      grid.build(light.photon_pos, it.radius);
      light.gather_photons(grid.order());
      light.photon_pos = {};  // the grid holds its own copy
      ++totals.grid_builds;
    } else {
      grid.build({}, it.radius);
    }
    std::fill(iter.begin(), iter.end(), Rgbd::Zero());
    std::fill(tile_counters.begin(), tile_counters.end(), VcmCameraCounters{});
    if (m_settings.mode != VcmMode::lt) {
      const VcmCameraTracer tracer(scene, m_settings, it, light, grid);
      std::vector<char> tile_done(tile_counters.size(), 0);
      core::parallel_for(
          int64_t(tile_counters.size()), threads,
          [&](int64_t ti, int thread) {
            const Tile tile{int(ti), int(ti % tiles_x) * kTileSize, int(ti / tiles_x) * kTileSize,
                            std::min(w, int(ti % tiles_x + 1) * kTileSize), std::min(h, int(ti / tiles_x + 1) * kTileSize)};
            core::Rng rng(options.seed, (uint64_t(global) << 32) | 0x80000000ull | uint64_t(ti));
            VcmCameraScratch& sc = scratch[size_t(thread)];
            VcmCameraCounters& cc = tile_counters[size_t(ti)];
            for (int y = tile.y0; y < tile.y1; ++y)
              for (int x = tile.x0; x < tile.x1; ++x) {
                const Vec2 raster(float(x) + rng.uniform(), float(y) + rng.uniform());
                const int64_t p = int64_t(y) * w + x;
                Rgb L = Rgb::Zero();
                if (tracer.sample(raster, p, rng, sc, L, cc)) iter[size_t(p)] = L.cast<double>();
              }
            tile_done[size_t(ti)] = 1;
          },
          options.stop);
      if (std::find(tile_done.begin(), tile_done.end(), 0) != tile_done.end()) {
        interrupted = true;
        break;
      }
    }
    // Light tracing: N = pixel count light paths, so a splat adds its value as is.
    for (const LightChunk& c : light.chunks)
      for (const Splat& s : c.splats) iter[size_t(s.pixel)] += s.value.cast<double>();
    for (size_t i = 0; i < total.size(); ++i) total[i] += iter[i];
    for (const VcmCameraCounters& c : tile_counters) totals.camera += c;
    totals.light += lc;
    totals.photons += m_settings.merges() ? int64_t(light.photons.size()) : 0;
    light.release_photons();
    grid.release();
    radius = it.radius;
    ++done;
    if (timed) progress.set_fraction(std::min(1.0, timer.seconds() / options.time_budget));
    else progress.advance();
  }
  progress.finish();

  RenderResult result = finish_iterations([this](const core::RawImage& r, const RenderOptions& o) { return finish(r, o); },
                                          w, h, std::move(total), done, target, interrupted, options);
  write_counters(totals, done, done * pixels, result.stats);
  result.wall_seconds = timer.seconds();
  result.info["passes"] = done;
  result.info["mode"] = VcmSettings::mode_name(m_settings.mode);
  result.info["radius_initial"] = double(r0);
  result.info["radius_final"] = double(radius);
  result.info["light_paths"] = double(done * pixels);
  return result;
}

RenderResult VcmIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return finish_radiance(raw, options);  // the iterations' sum over their count, as path's
}

}  // namespace dp::integrators
