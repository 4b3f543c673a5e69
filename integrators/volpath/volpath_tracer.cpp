#include "integrators/volpath/volpath_tracer.h"

#include <algorithm>
#include <cmath>

#include "integrators/path/path_tracer.h"  // power_heuristic
#include "pathspace/scatter.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

using scene::BsdfContext;
using scene::SurfaceHit;
using pathspace::consistent_side;

void VolpathCounters::flush(core::Stats& stats) const {
  stats.add("volpath.rays", rays);
  stats.add("volpath.shadow_rays", shadow_rays);
  stats.add("volpath.rr_terminated", rr_terminated);
  stats.add("volpath.medium_scatter", medium_scatter);
  stats.add("volpath.medium_pass", medium_pass);
  stats.add("volpath.surface_events", surface_events);
  stats.add("volpath.null_crossings", null_crossings);
  stats.add("volpath.shadow_null_crossings", shadow_null_crossings);
  stats.add("volpath.fail.null_limit", null_limit);
  stats.add("volpath.media_skipped", media_skipped);
  stats.add("volpath.grid_flights", grid_flights);
  stats.add("volpath.equiangular.samples", equiangular_samples);
  stats.add("volpath.equiangular.skipped", equiangular_skipped);
  stats.add("volpath.equiangular.occluded", equiangular_occluded);
  stats.add("volpath.mnee.attempts", mnee_attempts);
  stats.add("volpath.mnee.chains", mnee_chains);
  stats.add("volpath.mnee.shape_attempts", mnee_shape_attempts);
  stats.add("volpath.mnee.fail.seed", mnee_seed_failed);
  stats.add("volpath.mnee.fail.walk", mnee_walk_failed);
  stats.add("volpath.mnee.fail.occluded", mnee_occluded);
  stats.add("volpath.mnee.connections", mnee_connections);
  stats.add("volpath.mnee.scan.rays", mnee_scan_rays);
  stats.add("volpath.mnee.scan.brackets", mnee_scan_brackets);
  stats.add("volpath.mnee.scan.folds", mnee_scan_folds);
  stats.add("volpath.mnee.scan.edges", mnee_scan_edges);
  stats.add("volpath.mnee.scan.fallbacks", mnee_scan_fallbacks);
  stats.add("volpath.mnee.bsdf_hits", mnee_bsdf_hits);
  stats.add("volpath.mnee.bsdf_matched", mnee_bsdf_matched);
  stats.add("volpath.light.paths", light_paths);
  stats.add("volpath.light.chains", light_chains);
  stats.add("volpath.light.links", light_links);
  stats.add("volpath.light.blocked", light_blocked);
  stats.add("volpath.light.unmatched", light_unmatched);
  stats.add("volpath.light.added", light_added);
  if (mnee_walks.attempted > 0) mnee_walks.flush(stats, "volpath.mnee.walk");
  if (mnee_seeds.attempted > 0) mnee_seeds.flush(stats, "volpath.mnee.seed");
}

namespace {

// Russian roulette after rr_depth segments, survival min(0.95, max throughput component).
bool survive(Rgb& beta, int depth, int rr_depth, core::Rng& rng, VolpathCounters& c) {
  if (depth < rr_depth) return true;
  const float q = std::min(0.95f, max_component(beta));
  if (!(rng.uniform() < q)) {
    ++c.rr_terminated;
    return false;
  }
  beta /= q;
  return true;
}

}  // namespace

VolpathTracer::VolpathTracer(const scene::Scene& scene, const VolpathSettings& settings, int max_depth)
    : m_scene(scene),
      m_settings(settings),
      m_max_depth(max_depth),
      m_has_media(scene.caps().has_media),
      m_camera_medium(scene.camera_medium()),
      m_mnee(false),
      m_equiangular(m_has_media && settings.equiangular && settings.nee),
      m_light_tracing(false) {
  if (!m_has_media || !settings.mnee || !settings.nee) return;
  for (const auto& b : scene.bsdfs())
    if (b && b->is_purely_delta() && (b->lobes() & scene::kDeltaTransmission) != 0) m_mnee = true;
  set_light_tracing();
  if (!settings.mnee_shapes) return;
  for (size_t i = 0; i < scene.shapes().size(); ++i) {
    const int mat = scene.shapes()[i]->material;
    const scene::Bsdf* b = mat >= 0 ? scene.bsdfs()[size_t(mat)].get() : nullptr;
    if (b && b->is_purely_delta() && (b->lobes() & (scene::kDeltaReflection | scene::kDeltaTransmission)) != 0)
      m_shapes.push_back(int(i));
  }
  if (m_shapes.size() > size_t(kMaxMneeShapes)) m_shapes.clear();
  if (!m_shapes.empty()) m_mnee = true;
  set_light_tracing();
}

VolpathTracer::MarchEnd VolpathTracer::march(Ray r, int& medium, const Vec3* target, core::Rng& rng,
                                             VolpathCounters& c, Rgb& tr, SurfaceHit& h, double* flight,
                                             bool scatter_at_origin) const {
  tr = Rgb::Ones();
  for (int crossings = 0;; ++crossings) {
    const bool found = m_scene.intersect(r, h);
    // Beer-Lambert over the part of the segment inside this medium (Gruson et al. 2018,
    // Eq. 2: tau of the NEE edge).
    // A grid medium: ratio tracking (grid_tracking.h), an unbiased estimate of the same.
    if (medium >= 0 && m_settings.fault != VolpathFault::nee_without_transmittance) {
      const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
      const float len = found ? h.t : r.tmax;
      tr *= med.heterogeneous() ? scene::transmittance_grid(med, r.o, r.d, len, rng) : scene::transmittance(med, len);
      if (flight)
        *flight *= double(crossings == 0 && scatter_at_origin ? scene::free_flight_pdf(med, len)
                                                              : scene::free_flight_pass_probability(med, len));
    }
    if (!found) return MarchEnd::reached;
    if (!scene::is_index_matched(h)) return MarchEnd::surface;  // an opaque or refractive surface
    if (crossings >= kMaxNullCrossings) {
      ++c.null_limit;
      return MarchEnd::limit;
    }
    ++c.shadow_null_crossings;
    if (is_black(tr)) return MarchEnd::reached;
    medium = scene::medium_toward(h, r.d, medium, m_camera_medium);
    r = target ? m_scene.spawn_segment(h, *target) : m_scene.spawn_ray(h, r.d);
  }
}

Rgb VolpathTracer::shadow_transmittance(Ray r, int medium, const Vec3* target, core::Rng& rng, VolpathCounters& c) const {
  Rgb tr;
  SurfaceHit h;
  return march(r, medium, target, rng, c, tr, h) == MarchEnd::reached ? tr : Rgb::Zero();
}

template <bool kMedia>
Rgb VolpathTracer::next_event_surface(const SurfaceHit& hit, const Vec3& wi_local, const BsdfContext& ctx, int medium,
                                      core::Rng& rng, VolpathCounters& c, NeeProbe* probe) const {
  const float u_light = rng.uniform();
  const Vec2 u = rng.uniform2();
  float pmf;
  const scene::Emitter* emitter = m_scene.sample_emitter(u_light, pmf);
  if (!emitter) return Rgb::Zero();
  const scene::DirectSample ds = emitter->sample_direct(hit.p, u);
  // MNEE may reach the light point where the straight direction has no contribution,
  // even from behind the light (a chain turns around: a reflection off a ball below it).
  if (probe) set_probe(*probe, ds);
  if (!(ds.pdf > 0.0f) || is_black(ds.radiance)) return Rgb::Zero();
  const Vec3 wo_local = hit.shading.to_local(ds.wi);
  if (!consistent_side(hit, ds.wi, wo_local.z())) return Rgb::Zero();
  float bsdf_pdf;  // pdf of sampling wo by the BSDF, for the MIS weight
  const Rgb f = hit.bsdf->eval_pdf(ctx, wi_local, wo_local, bsdf_pdf) * abs_cos_theta(wo_local);
  if (is_black(f)) return Rgb::Zero();
  ++c.shadow_rays;
  const bool finite = std::isfinite(ds.dist);
  const Ray r = finite ? m_scene.spawn_segment(hit, ds.p) : m_scene.spawn_ray(hit, ds.wi);
  Rgb tr = Rgb::Ones();
  if constexpr (kMedia) {
    int light_side = scene::medium_toward(hit, ds.wi, medium, m_camera_medium);
    SurfaceHit blocker;
    const MarchEnd end = march(r, light_side, finite ? &ds.p : nullptr, rng, c, tr, blocker);
    if (probe) probe->try_chain = end == MarchEnd::surface && mnee_refracts(blocker);
    if (end != MarchEnd::reached || is_black(tr)) return Rgb::Zero();
  } else {
    (void)medium;
    if (m_scene.occluded(r)) return Rgb::Zero();
  }
  const float light_pdf = pmf * ds.pdf;
  const float weight = ds.delta ? 1.0f : power_heuristic(light_pdf, bsdf_pdf);
  return f * tr * ds.radiance * (weight / light_pdf);
}

template Rgb VolpathTracer::next_event_surface<true>(const SurfaceHit&, const Vec3&, const BsdfContext&, int,
                                                     core::Rng&, VolpathCounters&, NeeProbe*) const;
template Rgb VolpathTracer::next_event_surface<false>(const SurfaceHit&, const Vec3&, const BsdfContext&, int,
                                                      core::Rng&, VolpathCounters&, NeeProbe*) const;

Rgb VolpathTracer::next_event_medium(const Vec3& p, const Vec3& d, int medium, core::Rng& rng, VolpathCounters& c,
                                     NeeProbe* probe, const FlightSegment* flight) const {
  const float u_light = rng.uniform();
  const Vec2 u = rng.uniform2();
  float pmf;
  const scene::Emitter* emitter = m_scene.sample_emitter(u_light, pmf);
  if (!emitter) return Rgb::Zero();
  const scene::DirectSample ds = emitter->sample_direct(p, u);
  if (probe) set_probe(*probe, ds);  // as next_event_surface
  if (!(ds.pdf > 0.0f) || is_black(ds.radiance)) return Rgb::Zero();
  // The medium vertex's rho = sigma_s * rho_p (Gruson et al. 2018, Eq. 3); sigma_s is
  // already in the throughput (free-flight weight), G has no cosines here (Eq. 4).
  const float phase = scene::HenyeyGreenstein(m_scene.media()[size_t(medium)].phase).eval(d, ds.wi);
  if (!(phase > 0.0f)) return Rgb::Zero();
  ++c.shadow_rays;
  Ray r;
  r.o = p;
  r.d = ds.wi;
  r.tmin = 0.0f;
  const bool finite = std::isfinite(ds.dist);
  r.tmax = finite ? std::max(0.0f, ds.dist - 2.0f * scene::Scene::epsilon_at(ds.p))
                  : kInfinity;
  Rgb tr;
  SurfaceHit blocker;
  const MarchEnd end = march(r, medium, finite ? &ds.p : nullptr, rng, c, tr, blocker);
  if (probe) probe->try_chain = end == MarchEnd::surface && mnee_refracts(blocker);
  if (end != MarchEnd::reached || is_black(tr)) return Rgb::Zero();
  const float light_pdf = pmf * ds.pdf;
  // MIS with phase sampling and, on a flight segment, equiangular sampling
  // (volpath_equiangular.cpp); the phase pdf is the phase value.
  const float R = flight ? equiangular_ratio(*flight, *emitter, pmf, ds.p, ds.n) : 0.0f;
  float weight = ds.delta ? power_heuristic(1.0f, R, 0.0f) : power_heuristic(light_pdf, phase, R);
  if (m_settings.fault == VolpathFault::medium_nee_without_mis) weight = 1.0f;
  return tr * ds.radiance * (phase * weight / light_pdf);
}

template <bool kMedia>
Rgb VolpathTracer::trace(const Ray& primary, core::Rng& rng, VolpathCounters& c, const LightEnd* light) const {
  Rgb L = Rgb::Zero(), beta = Rgb::Ones();
  Ray ray = primary;
  bool prev_delta = true;  // the camera is a "delta" for MIS: directly seen lights count fully
  float prev_pdf = 0.0f;   // solid-angle pdf of the last BSDF or phase sample
  Vec3 prev_p = primary.o; // the last scattering vertex (index-matched boundaries are not vertices)
  int medium = kMedia ? m_camera_medium : -1;
  [[maybe_unused]] int nulls = 0;  // index-matched boundaries crossed (media only)
  const scene::EnvironmentEmitter* env = m_scene.environment();
  SurfaceHit hit;
  if constexpr (!kMedia) ++c.media_skipped;
  // After a surface vertex (or an index-matched crossing) the path continues by the one
  // rule of every integrator and shift, Scene::trace_from; ray.o is then that vertex.
  bool from_surface = false;
  ChainTrack chain;  // MNEE's view of the path since its last non-specular vertex
  FlightSegment flight;  // the last vertex's free-flight segment, if it was a medium vertex (equiangular MIS)
  // Light tracing (volpath_light.cpp): the last vertex, where the camera path can be joined
  // to a light path (none after a Dirac sample), and the light path to join.
  CameraVertex prev_v = m_light_tracing ? camera_vertex() : CameraVertex{};
  if (light && !light->ok) light = nullptr;
  for (int depth = 1; depth <= m_max_depth;) {
    const bool found = from_surface ? m_scene.trace_from(hit, ray.d, hit) : m_scene.intersect(ray, hit);
    ++c.rays;
    if constexpr (kMedia) {
      if (medium >= 0) {
        const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
        const float t_max = found ? hit.t : kInfinity;
        const bool equiangular = m_equiangular && depth < m_max_depth;
        if (equiangular) L += beta * next_event_equiangular(ray, t_max, medium, rng, c);
        scene::FreeFlightSample ff;
        if (med.heterogeneous()) {  // delta tracking (grid_tracking.h)
          ++c.grid_flights;
          ff = scene::sample_free_flight_grid(med, ray.o, ray.d, t_max, rng);
        } else {
          const float u_channel = rng.uniform(), u_distance = rng.uniform();
          ff = scene::sample_free_flight(med, t_max, u_channel, u_distance);
        }
        Rgb w = ff.weight;
        if (m_settings.fault == VolpathFault::pass_without_probability && !ff.scattered)
          w = scene::transmittance(med, ff.t);
        beta *= w;
        if (ff.scattered) {
          ++c.medium_scatter;
          if (depth == m_max_depth || is_black(beta)) break;
          const Vec3 p = ray.at(ff.t);
          flight = FlightSegment{};
          if (equiangular) flight = FlightSegment{true, ray.o, ray.d, t_max, ff.t, flight_pdf(medium, ray.o, ray.d, ff.t)};
          const FlightSegment* fs = flight.active ? &flight : nullptr;
          if (m_mnee) {  // NEE, then MNEE with its light sample (volpath_mnee.h)
            NeeProbe probe;
            L += beta * next_event_medium(p, ray.d, medium, rng, c, &probe, fs);
            chain.start(linked(MneeAnchor::in_medium(p, ray.d, medium, depth), prev_v), prev_v);
            if (probe.area_light) L += beta * mnee_nee(chain.anchor, probe, chain.prev, rng, c);
            if (m_light_tracing) {  // this vertex, joined to the light path and kept for the next anchor
              prev_v = CameraVertex::of(chain.anchor, beta);
              if (light) L += connect_light(*light, prev_v, rng, c);
            }
          } else if (m_settings.nee) {
            L += beta * next_event_medium(p, ray.d, medium, rng, c, nullptr, fs);
          }
          const scene::HenyeyGreenstein phase(med.phase);
          const Vec3 wo = phase.sample(ray.d, rng.uniform2());
          // Phase sampling is exact: the weight rho_p / pdf is 1, beta is unchanged.
          prev_pdf = phase.pdf(ray.d, wo);
          prev_delta = false;
          prev_p = p;
          if (!survive(beta, depth, m_settings.rr_depth, rng, c)) break;
          ray.o = p;
          ray.d = wo;
          ray.tmin = 0.0f;
          ray.tmax = kInfinity;
          from_surface = false;
          ++depth;
          continue;
        }
        ++c.medium_pass;
        if (is_black(beta)) break;
      }
    }
    const bool hide = depth == 1 && m_settings.hide_emitters;
    if (!found) {
      if (env && !hide) {
        const Rgb Le = env->eval_direction(ray.d);
        float w = 1.0f;
        if (!prev_delta && m_settings.nee)
          w = power_heuristic(prev_pdf, m_scene.emitter_pmf(env) * env->pdf_direct(prev_p, {}, {}, ray.d));
        L += beta * Le * w;
      }
      break;
    }
    if (hit.emitter && !hide) {
      const Rgb Le = hit.emitter->eval(hit, -ray.d);
      if (!is_black(Le)) {
        float w = 1.0f;
        if (!prev_delta && m_settings.nee) {
          const float pmf = m_scene.emitter_pmf(hit.emitter);
          const float light_pdf = pmf * hit.emitter->pdf_direct(prev_p, hit.p, hit.ng, ray.d);
          const float R = flight.active ? equiangular_ratio(flight, *hit.emitter, pmf, hit.p, hit.ng) : 0.0f;
          w = power_heuristic(prev_pdf, light_pdf, R);
        } else if (kMedia && m_mnee && chain.active && chain.m > 0) {
          w = mnee_bsdf_weight(chain, hit, rng, c);
        }
        L += beta * Le * w;
      }
    }
    if constexpr (kMedia) {
      if (scene::is_index_matched(hit)) {  // not a vertex: switch media, keep the direction and depth
        ++c.null_crossings;
        if (++nulls > kMaxNullCrossings) {
          ++c.null_limit;
          break;
        }
        medium = scene::medium_toward(hit, ray.d, medium, m_camera_medium);
        ray = m_scene.continue_ray(hit, ray.d);
        from_surface = true;
        continue;
      }
    }
    if (depth == m_max_depth || !hit.bsdf) break;
    const Vec3 wi_local = hit.shading.to_local(-ray.d);
    if (!consistent_side(hit, -ray.d, wi_local.z())) break;
    ++c.surface_events;
    const BsdfContext ctx{hit.uv, scene::TransportMode::radiance};
    MneeAnchor anchor;  // MNEE's anchor at a non-Dirac surface vertex (prev_v: the camera vertex before it)
    if (kMedia && m_mnee && !hit.bsdf->is_purely_delta())
      anchor = linked(MneeAnchor::at_surface(hit, wi_local, medium, depth), prev_v);
    if (kMedia && light && !hit.bsdf->is_purely_delta())  // joined to the light path
      L += connect_light(*light, CameraVertex::of(anchor, beta), rng, c);
    if (m_settings.nee && !hit.bsdf->is_purely_delta()) {
      NeeProbe probe;
      L += beta * next_event_surface<kMedia>(hit, wi_local, ctx, medium, rng, c, kMedia && m_mnee ? &probe : nullptr);
      if (kMedia && probe.area_light) L += beta * mnee_nee(anchor, probe, prev_v, rng, c);  // MNEE with NEE's light sample
    }

    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = hit.bsdf->sample(ctx, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!consistent_side(hit, wo, bs->wo.z())) break;
    if (kMedia && m_mnee) {  // the anchor x, or one more refraction after it (volpath_mnee.h)
      if (!bs->is_delta()) {
        chain.start(anchor, prev_v);
      } else if (chain.active && chain.m < kMaxMneeChain &&
                 (bs->lobe == scene::kDeltaReflection || (bs->lobe == scene::kDeltaTransmission && bs->eta != 1.0f))) {
        if (bs->lobe == scene::kDeltaReflection) chain.reflect_mask |= 1u << chain.m;
        chain.verts[size_t(chain.m++)] = hit.p;
      } else {
        chain.active = false;
      }
    }
    if (kMedia && m_light_tracing)  // the next anchor's camera vertex (none after a Dirac lobe)
      prev_v = bs->is_delta() ? CameraVertex{} : CameraVertex::of(anchor, beta);
    beta *= bs->weight;
    flight.active = false;
    prev_delta = bs->is_delta();
    prev_pdf = bs->pdf;
    prev_p = hit.p;
    if constexpr (kMedia) medium = scene::medium_toward(hit, wo, medium, m_camera_medium);
    if (!survive(beta, depth, m_settings.rr_depth, rng, c)) break;
    ray = m_scene.continue_ray(hit, wo);
    from_surface = true;
    ++depth;
  }
  return L;
}

Rgb VolpathTracer::radiance(const Ray& ray, core::Rng& rng, VolpathCounters& counters, const LightEnd* light) const {
  return m_has_media ? trace<true>(ray, rng, counters, light) : trace<false>(ray, rng, counters, nullptr);
}

}  // namespace dp::integrators
