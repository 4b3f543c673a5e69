#include "integrators/gvpm/gvpm_integrator.h"

#include <algorithm>
#include <memory>

#include "core/progress.h"
#include "core/thread_pool.h"
#include "core/timer.h"
#include "integrators/gradient_passes.h"
#include "integrators/gvpm/gvpm_tracer.h"
#include "integrators/iteration_share.h"
#include "integrators/media_photons/media_photon_render.h"
#include "integrators/media_photons/volume_kernel.h"
#include "integrators/tile_scheduler.h"
#include "integrators/beam/beam_gather.h"
#include "integrators/plane/plane_gather.h"
#include "integrators/plane/plane_pass.h"
#include "integrators/bre/bre_gather.h"
#include "integrators/vpm/vpm_gather.h"

namespace dp::integrators {

RenderResult GvpmIntegrator::render(const scene::Scene& scene, const RenderOptions& options) {
  // The iteration loop of media_photon_render.cpp with gradient buffers (as photon_iterations.cpp).
  const auto& cam = scene.camera();
  const int w = cam.width(), h = cam.height();
  const int threads = resolve_threads(options);
  const bool timed = options.time_budget > 0;
  const bool media = scene.caps().has_media;
  const IterationShare share(options);
  const int64_t target = share.target;
  const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;
  const int64_t tiles = int64_t(tiles_x) * tiles_y;
  const double r1 = initial_media_radius(scene, m_settings);
  const std::string prefix = m_settings.name();  // gvpm | gbre
  const bool beam = m_settings.gather == GvpmGather::beam;
  const bool beams = m_settings.gather == GvpmGather::beams, planes = m_settings.gather == GvpmGather::planes;
  // The gathers of the unshifted camera segments (after the first surface): vpm's, or for
  // gbre bre's Point-Beam 3D (the same estimator as its shifted gathers, integrated).
  VpmSettings vpm;
  static_cast<MediaPhotonSettings&>(vpm) = m_settings;
  vpm.distance_samples = m_settings.distance_samples;
  BreSettings bre;
  static_cast<MediaPhotonSettings&>(bre) = m_settings;
  bre.kernel_dim = 3;
  BeamSettings beam_settings;  // gbeam's later segments: beam's Beam-Beam 3D
  static_cast<MediaPhotonSettings&>(beam_settings) = m_settings;
  beam_settings.kernel = BeamKernel::k3d;
  std::vector<gradients::PhotonParent> beam_parents;
  BeamBvh beam_bvh;
  BeamTraceCounters beam_counters;
  PlaneSettings plane_settings;  // gplane's later segments: plane's gather (planes + Beam-Beam 3D)
  static_cast<MediaPhotonSettings&>(plane_settings) = m_settings;
  plane_settings.piece_scale = m_settings.plane_piece_scale;
  PlaneBvh plane_bvh;
  PlanePassCounters plane_counters;

  GatherCounterNames names;  // gplane: also the plane tests, intersections and occluded
  names.planes = planes;
  GradientPasses passes;
  passes.total = gradients::GradientBuffers(w, h);
  std::vector<core::Stats> thread_stats(static_cast<size_t>(threads)), iter_stats(static_cast<size_t>(threads));
  std::vector<gradients::GradientBuffers> buffers(static_cast<size_t>(threads), gradients::GradientBuffers(w, h));
  std::vector<GvpmScratch> scratch(static_cast<size_t>(threads));
  std::vector<gradients::PhotonParent> parents;
  std::vector<gradients::PhotonChain> chains;  // specular chains, recorded only for the manifold walk
  std::vector<gradients::PhotonChain>* chains_out = m_settings.manifold ? &chains : nullptr;
  PhotonTraceCounters photon_counters;
  PhotonBvh bvh;
  core::Timer timer;
  core::Progress progress(prefix, timed ? 1000 : target, options.quiet);
  int64_t done = 0;
  double radius = r1;
  while (timed ? timer.seconds() < options.time_budget : done < target) {
    if (options.stop && options.stop->load()) {
      passes.partial = true;
      break;
    }
    const int64_t global = share.global(done);
    const float r = float(progressive_radius(r1, global, m_settings.radius_alpha, 3));
    PhotonTraceCounters pc;
    std::unique_ptr<MediumGather> later, primary_unshifted;
    if (media) {  // no photon is traced for a scene without media
      const PhotonTraceParams tp = photon_pass_params(m_settings, options, global, threads);
      std::vector<MediumPhoton> photons;
      if (planes) {  // planes and the beams not from scattering events, as `plane` (plane_pass.h)
        if (!trace_plane_pass(scene, tp, options.stop, r, m_settings.plane_piece_scale, false, pc, plane_counters,
                              beam_bvh, plane_bvh)) {
          passes.partial = true;
          break;
        }
        later = std::make_unique<PlaneGather>(scene, plane_settings, beam_settings, beam_bvh, plane_bvh, r, tp.paths);
        primary_unshifted = std::make_unique<BeamGather>(scene, beam_settings, beam_bvh, r, tp.paths);
      } else if (beams) {  // only the light paths' beams are kept, with their parents (photon_tracer.h)
        PhotonTraceParams tb = tp;
        tb.store_photons = false;
        std::vector<MediumBeam> traced;
        BeamTraceCounters bc;
        if (!trace_medium_photons(scene, tb, options.stop, photons, pc, &parents, &traced, &bc, &beam_parents,
                                  nullptr, nullptr, chains_out)) {
          passes.partial = true;
          break;
        }
        beam_counters += bc;
        const float piece = beam_piece_length(scene, traced, r);
        beam_bvh.build(std::move(traced), piece);
        later = std::make_unique<BeamGather>(scene, beam_settings, beam_bvh, r, tp.paths);
      } else {
        if (!trace_medium_photons(scene, tp, options.stop, photons, pc, &parents, nullptr, nullptr, nullptr, nullptr,
                                  nullptr, chains_out)) {
          passes.partial = true;
          break;
        }
        bvh.build(std::move(photons));
        if (beam) later = std::make_unique<BreGather>(scene, bre, bvh, r, tp.paths);
        else later = std::make_unique<VpmGather>(scene, vpm, bvh, r, tp.paths);
      }
    }
    GvpmLightData data;
    if (media) {
      data.photons = &bvh;
      data.parents = beams ? &beam_parents : &parents;
      data.chains = &chains;
      data.beams = &beam_bvh;
      data.planes = &plane_bvh;
      data.later = later.get();
      data.primary_unshifted = primary_unshifted.get();
      data.light_paths = int64_t(m_settings.photons);
    }
    const GvpmTracer tracer(scene, m_settings, options.max_depth, r, data);
    for (auto& s : iter_stats) s = core::Stats{};
    std::vector<char> tile_done(static_cast<size_t>(tiles), 0);
    core::parallel_for(
        tiles, threads,
        [&](int64_t ti, int thread) {
          const int x0 = int(ti % tiles_x) * kTileSize, y0 = int(ti / tiles_x) * kTileSize;
          core::Rng rng(options.seed, (uint64_t(global) << 32) | 0x60000000ull | uint64_t(ti));
          GvpmCounters counters;
          for (int y = y0; y < std::min(h, y0 + kTileSize); ++y)
            for (int x = x0; x < std::min(w, x0 + kTileSize); ++x)
              tracer.sample(x, y, rng, scratch[size_t(thread)], buffers[size_t(thread)], counters);
          counters.flush(iter_stats[size_t(thread)], prefix, names);
          tile_done[size_t(ti)] = 1;
        },
        options.stop);
    bvh.release();
    beam_bvh.release();
    plane_bvh.release();
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
    photon_counters += pc;
    radius = r;
    ++done;
    if (timed) progress.set_fraction(std::min(1.0, timer.seconds() / options.time_budget));
    else progress.advance();
  }
  progress.finish();
  passes.passes = passes.kept = done;
  passes.partial = passes.partial || (!timed && done < target);
  passes.render_seconds = timer.seconds();

  core::Json settings = m_json;
  RenderResult result = options.raw ? gradient_raw_result(passes, thread_stats)
                                    : gradient_result(passes, thread_stats, m_settings.alpha, m_settings.reconstruction,
                                                      options, settings);
  photon_counters.flush(result.stats, prefix);
  result.stats.add(prefix + ".iterations", done);
  if (!media) result.stats.add(prefix + ".photon_passes_skipped", done);
  if (beams) {
    result.stats.add(prefix + ".beams_stored", beam_counters.stored);
    result.stats.add(prefix + ".beams_clipped", beam_counters.clipped);
    result.stats.add(prefix + ".beam_nan_dropped", beam_counters.dropped);
  }
  if (planes) plane_counters.flush(result.stats, prefix);
  result.info["media"] = media;
  result.info["kernel_dimension"] = planes ? 0 : 3;
  result.info["radius_initial"] = r1;
  result.info["radius_final"] = radius;
  result.info["photons_per_iteration"] = m_settings.photons;
  result.info["gather"] = planes  ? "planes (Plane-Beam 0D; beams not from scattering events: Beam-Beam 3D, unshifted)"
                          : beams ? "beams (Beam-Beam 3D)"
                          : beam  ? "beam (Point-Beam 3D)"
                                  : "points";
  if (planes) result.info["plane_piece_scale"] = m_settings.plane_piece_scale;
  if (!beam && !beams) result.info["distance_samples"] = m_settings.distance_samples;
  if (!planes) result.info["mixed_shift"] = m_settings.mixed;
  result.wall_seconds = timer.seconds();
  return result;
}

RenderResult GvpmIntegrator::finish(const core::RawImage& raw, const RenderOptions& options) const {
  return gradient_finish(raw, options, m_settings.alpha, m_settings.reconstruction, m_json);
}

}  // namespace dp::integrators
