#include "integrators/media_photons/media_photon_render.h"

#include <algorithm>
#include <cmath>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/iteration_share.h"
#include "integrators/media_photons/volume_kernel.h"
#include "integrators/radiance_render.h"
#include "integrators/raw_result.h"
#include "integrators/tile_scheduler.h"

namespace dp::integrators {

double initial_media_radius(const scene::Scene& scene, const MediaPhotonSettings& settings) {
  const double diag = double(scene.bounds().diagonal());
  return settings.radius_scale * (diag > 0.0 && std::isfinite(diag) ? diag : 1.0);
}

PhotonTraceParams photon_pass_params(const MediaPhotonSettings& settings, const RenderOptions& options, int64_t global,
                                     int threads) {
  PhotonTraceParams tp;
  tp.paths = settings.photons;
  tp.max_depth = options.max_depth;
  tp.rr_depth = settings.rr_depth;
  tp.seed = options.seed;
  tp.iteration = global;
  tp.threads = threads;
  return tp;
}

RenderResult render_media_photons(const scene::Scene& scene, const RenderOptions& options, const std::string& prefix,
                                  const MediaPhotonSettings& settings, int kernel_dim, const MakeGather& make_gather) {
  PhotonBvh bvh;
  MediaLightPass pass;
  pass.prepare = [&](const PhotonTraceParams& tp, float r, PhotonTraceCounters& pc, core::Stats&,
                     std::unique_ptr<MediumGather>& gather) {
    std::vector<MediumPhoton> photons;
    if (!trace_medium_photons(scene, tp, options.stop, photons, pc)) return false;
    bvh.build(std::move(photons));
    gather = make_gather(bvh, r, tp.paths);
    return true;
  };
  pass.release = [&] { bvh.release(); };
  return render_media_passes(scene, options, prefix, settings, kernel_dim, pass);
}

RenderResult render_media_passes(const scene::Scene& scene, const RenderOptions& options, const std::string& prefix,
                                 const MediaPhotonSettings& settings, int kernel_dim, const MediaLightPass& pass) {
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const bool media = scene.caps().has_media;
  const IterationShare share(options);
  const int64_t target = share.target;
  const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;
  const int64_t tiles = int64_t(tiles_x) * tiles_y;
  const double r1 = initial_media_radius(scene, settings);
  const MediaCameraTracer tracer(scene, settings.rr_depth, options.max_depth);

  std::vector<Rgbd> total(size_t(w) * size_t(h), Rgbd::Zero()), iter(total.size());
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads)), iter_stats(static_cast<size_t>(threads));
  PhotonTraceCounters photon_counters;
  core::Stats pass_stats;
  core::Timer timer;
  core::Progress progress(prefix, timed ? 1000 : target, options.quiet);
  int64_t done = 0;
  bool partial = false;
  double radius = r1;
  while (timed ? timer.seconds() < options.time_budget : done < target) {
    if (options.stop && options.stop->load()) {
      partial = true;
      break;
    }
    const int64_t global = share.global(done);
    const float r = float(progressive_radius(r1, global, settings.radius_alpha, kernel_dim));
    PhotonTraceCounters pc;
    core::Stats ps;
    std::unique_ptr<MediumGather> gather;
    if (media) {  // no photon is traced for a scene without media
      const PhotonTraceParams tp = photon_pass_params(settings, options, global, threads);
      if (!pass.prepare(tp, r, pc, ps, gather)) {
        partial = true;
        break;
      }
    }
    std::fill(iter.begin(), iter.end(), Rgbd::Zero());
    for (auto& s : iter_stats) s = core::Stats{};
    std::vector<char> tile_done(static_cast<size_t>(tiles), 0);
    core::parallel_for(
        tiles, threads,
        [&](int64_t ti, int thread) {
          const int x0 = int(ti % tiles_x) * kTileSize, y0 = int(ti / tiles_x) * kTileSize;
          const Tile tile{int(ti), x0, y0, std::min(w, x0 + kTileSize), std::min(h, y0 + kTileSize)};
          core::Rng rng(options.seed, (uint64_t(global) << 32) | 0x60000000ull | uint64_t(ti));
          MediaCameraCounters counters;
          const int64_t dropped = accumulate_tile(tile, 1, rng, w, iter, [&](const Vec2& raster, Rgb& L) {
            L = tracer.radiance(cam.generate_ray(raster), gather.get(), rng, counters);
            return is_finite(L);  // a non-finite sample is counted and dropped, never splatted
          });
          core::Stats& st = iter_stats[size_t(thread)];
          counters.flush(st, prefix, pass.names);
          st.add(prefix + ".nan_dropped", dropped);
          st.add(prefix + ".camera_paths", int64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0));
          tile_done[size_t(ti)] = 1;
        },
        options.stop);
    if (pass.release) pass.release();
    if (std::find(tile_done.begin(), tile_done.end(), 0) != tile_done.end()) {  // dropped whole
      partial = true;
      break;
    }
    for (size_t i = 0; i < total.size(); ++i) total[i] += iter[i];
    for (size_t t = 0; t < thread_stats.size(); ++t) thread_stats[t].merge(iter_stats[t]);
    photon_counters += pc;
    pass_stats.merge(ps);
    radius = r;
    ++done;
    if (timed) progress.set_fraction(std::min(1.0, timer.seconds() / options.time_budget));
    else progress.advance();
  }
  progress.finish();

  RenderResult result = finish_iterations(finish_radiance, w, h, std::move(total), done, target, partial, options);
  for (const auto& s : thread_stats) result.stats.merge(s);
  photon_counters.flush(result.stats, prefix);
  result.stats.merge(pass_stats);
  result.stats.add(prefix + ".iterations", done);
  if (!media) result.stats.add(prefix + ".photon_passes_skipped", done);
  result.info["media"] = media;
  result.info["kernel_dimension"] = kernel_dim;
  result.info["radius_initial"] = r1;
  result.info["radius_final"] = radius;
  result.info["photons_per_iteration"] = settings.photons;
  result.info["passes"] = done;
  result.wall_seconds = timer.seconds();
  return result;
}

}  // namespace dp::integrators
