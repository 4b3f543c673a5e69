#include "integrators/media_photons/media_camera.h"

#include <algorithm>

#include "integrators/path/path_tracer.h"  // power_heuristic
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium_interface.h"

namespace dp::integrators {

using scene::SurfaceHit;

void MediaCameraCounters::flush(core::Stats& stats, const std::string& prefix, const GatherCounterNames& names) const {
  stats.add(prefix + ".rays", surface.rays);
  stats.add(prefix + ".shadow_rays", surface.shadow_rays);
  stats.add(prefix + ".rr_terminated", surface.rr_terminated);
  stats.add(prefix + ".surface_events", surface.surface_events);
  stats.add(prefix + ".null_crossings", surface.null_crossings + surface.shadow_null_crossings);
  stats.add(prefix + ".fail.null_limit", surface.null_limit);
  stats.add(prefix + ".media_skipped", surface.media_skipped);
  stats.add(prefix + ".medium_segments", gather.segments);
  stats.add(prefix + "." + names.queries, gather.queries);
  stats.add(prefix + "." + names.gathered, gather.photons);
  stats.add(prefix + "." + names.depth_skipped, gather.depth_skipped);
  stats.add(prefix + ".empty_segments", gather.empty_segments);
  if (names.candidates) stats.add(prefix + "." + names.candidates, gather.candidates);
  if (names.parallel) stats.add(prefix + "." + names.parallel, gather.parallel);
  if (names.planes) {
    stats.add(prefix + ".plane_tests", gather.plane_tests);
    stats.add(prefix + ".intersections", gather.intersections);
    stats.add(prefix + ".plane_shadow_rays", gather.intersections);
    stats.add(prefix + ".occluded", gather.occluded);
  }
}

MediaCameraTracer::MediaCameraTracer(const scene::Scene& scene, int rr_depth, int max_depth)
    : m_scene(scene),
      m_volpath(scene,
                [&] {
                  VolpathSettings v;
                  v.rr_depth = rr_depth;
                  return v;
                }(),
                max_depth),
      m_rr_depth(rr_depth),
      m_max_depth(max_depth),
      m_has_media(scene.caps().has_media) {}

template <bool kMedia>
Rgb MediaCameraTracer::trace(const Ray& primary, const MediumGather* gather, core::Rng& rng,
                             MediaCameraCounters& counters) const {
  VolpathCounters& c = counters.surface;
  Rgb L = Rgb::Zero(), beta = Rgb::Ones();
  Ray ray = primary;
  bool prev_delta = true;
  float prev_pdf = 0.0f;
  Vec3 prev_p = primary.o;
  const int cam_medium = m_scene.camera_medium();
  int medium = kMedia ? cam_medium : -1;
  [[maybe_unused]] int nulls = 0;
  const scene::EnvironmentEmitter* env = m_scene.environment();
  SurfaceHit hit;
  if constexpr (!kMedia) ++c.media_skipped;
  bool from_surface = false;  // continue by Scene::trace_from after a surface (as volpath)
  for (int depth = 1; depth <= m_max_depth;) {
    const bool found = from_surface ? m_scene.trace_from(hit, ray.d, hit) : m_scene.intersect(ray, hit);
    ++c.rays;
    if constexpr (kMedia) {
      if (medium >= 0) {
        // The light scattered toward the camera along this segment (the photon estimate of
        // Eq. 5 on the camera edge), then the surface behind it through Tr (Eq. 2's tau).
        const float seg = found ? hit.t : kInfinity;
        ++counters.gather.segments;
        L += beta * gather->gather(ray, seg, medium, m_max_depth - depth, rng, counters.gather);
        const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
        // A grid medium's Tr by ratio tracking (grid_tracking.h: unbiased, as volpath's).
        beta *= med.heterogeneous() ? scene::transmittance_grid(med, ray.o, ray.d, seg, rng)
                                    : scene::transmittance(med, seg);
        if (is_black(beta)) break;
      }
    }
    if (!found) {
      if (env) {
        float w = 1.0f;
        if (!prev_delta)
          w = power_heuristic(prev_pdf, m_scene.emitter_pmf(env) * env->pdf_direct(prev_p, {}, {}, ray.d));
        L += beta * env->eval_direction(ray.d) * w;
      }
      break;
    }
    if (hit.emitter) {
      const Rgb Le = hit.emitter->eval(hit, -ray.d);
      if (!is_black(Le)) {
        float w = 1.0f;
        if (!prev_delta)
          w = power_heuristic(prev_pdf,
                              m_scene.emitter_pmf(hit.emitter) * hit.emitter->pdf_direct(prev_p, hit.p, hit.ng, ray.d));
        L += beta * Le * w;
      }
    }
    if constexpr (kMedia) {
      if (scene::is_index_matched(hit)) {  // not a vertex: switch media, keep direction and depth
        ++c.null_crossings;
        if (++nulls > VolpathTracer::kMaxNullCrossings) {
          ++c.null_limit;
          break;
        }
        medium = scene::medium_toward(hit, ray.d, medium, cam_medium);
        ray = m_scene.continue_ray(hit, ray.d);
        from_surface = true;
        continue;
      }
    }
    if (depth == m_max_depth || !hit.bsdf) break;
    const Vec3 wi_local = hit.shading.to_local(-ray.d);
    if (!(hit.ng.dot(-ray.d) * wi_local.z() > 0.0f)) break;  // sidedness, as volpath
    ++c.surface_events;
    const scene::BsdfContext ctx{hit.uv, scene::TransportMode::radiance};
    if (!hit.bsdf->is_purely_delta())
      L += beta * m_volpath.next_event_surface<kMedia>(hit, wi_local, ctx, medium, rng, c);
    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = hit.bsdf->sample(ctx, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!(hit.ng.dot(wo) * bs->wo.z() > 0.0f)) break;
    beta *= bs->weight;
    prev_delta = bs->is_delta();
    prev_pdf = bs->pdf;
    prev_p = hit.p;
    if constexpr (kMedia) medium = scene::medium_toward(hit, wo, medium, cam_medium);
    if (depth >= m_rr_depth) {  // Russian roulette as volpath's
      const float q = std::min(0.95f, max_component(beta));
      if (!(rng.uniform() < q)) {
        ++c.rr_terminated;
        break;
      }
      beta /= q;
    }
    ray = m_scene.continue_ray(hit, wo);
    from_surface = true;
    ++depth;
  }
  return L;
}

Rgb MediaCameraTracer::radiance(const Ray& ray, const MediumGather* gather, core::Rng& rng,
                                MediaCameraCounters& counters) const {
  return m_has_media ? trace<true>(ray, gather, rng, counters) : trace<false>(ray, gather, rng, counters);
}

}  // namespace dp::integrators
